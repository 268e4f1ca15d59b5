#include "plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace specula {

namespace {

const std::string& plotFont() {
    static const std::string font = [] {
        for (const char* f : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                              "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
                              "/usr/share/fonts/truetype/freefont/FreeSans.ttf"})
            if (std::filesystem::exists(f)) return std::string(f);
        return std::string();
    }();
    return font;
}

} // namespace

PlotCanvas::PlotCanvas(int width, int height, const PlotColour& background)
    : buf(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)) {
    OIIO::ImageBufAlgo::fill(buf, background);
}

void PlotCanvas::line(int x0, int y0, int x1, int y1, const PlotColour& c) {
    OIIO::ImageBufAlgo::render_line(buf, x0, y0, x1, y1, c);
}

void PlotCanvas::thickLine(int x0, int y0, int x1, int y1, const PlotColour& c) {
    for (int d = -1; d <= 1; ++d) {
        line(x0 + d, y0, x1 + d, y1, c);
        line(x0, y0 + d, x1, y1 + d, c);
    }
}

void PlotCanvas::dashed(int x0, int y0, int x1, int y1, const PlotColour& c) {
    const double len = std::hypot(double(x1 - x0), double(y1 - y0));
    const int n = std::max(1, int(len / 6.0));
    for (int i = 0; i < n; i += 2) {
        const double a = double(i) / n, b = double(std::min(i + 1, n)) / n;
        line(int(x0 + a * (x1 - x0)), int(y0 + a * (y1 - y0)), int(x0 + b * (x1 - x0)),
             int(y0 + b * (y1 - y0)), c);
    }
}

void PlotCanvas::box(int x0, int y0, int x1, int y1, const PlotColour& c, bool fill) {
    OIIO::ImageBufAlgo::render_box(buf, x0, y0, x1, y1, c, fill);
}

void PlotCanvas::text(int x, int y, const std::string& s, int size, const PlotColour& c,
                      OIIO::ImageBufAlgo::TextAlignX ax, OIIO::ImageBufAlgo::TextAlignY ay) {
    if (plotFont().empty()) return; // no font on this machine: the plot has no text
    OIIO::ImageBufAlgo::render_text(buf, x, y, s, size, plotFont(), c, ax, ay);
}

Image PlotCanvas::image() const {
    const OIIO::ImageSpec& spec = buf.spec();
    Image out(spec.width, spec.height, 3);
    buf.get_pixels(OIIO::ROI(0, spec.width, 0, spec.height, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT,
                   out.pixels.data());
    return out;
}

std::string plotNumber(const char* format, double v) {
    char b[64];
    std::snprintf(b, sizeof b, format, v);
    return b;
}

} // namespace specula
