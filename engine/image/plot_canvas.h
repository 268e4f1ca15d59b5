#pragma once
// A small canvas for the project's plots (PNG figures in docs/bench.md): lines, boxes and text on
// an RGB float image, drawn with OpenImageIO's render_line / render_box / render_text. Text
// needs a TrueType font from the system (DejaVu, Liberation or FreeSans); without one the
// plot is drawn without its text.
#include "engine/image/image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <array>
#include <string>

namespace specula {

using PlotColour = std::array<float, 3>;

struct PlotCanvas {
    OIIO::ImageBuf buf;

    // A width x height canvas filled with `background`.
    PlotCanvas(int width, int height, const PlotColour& background = {0.035f, 0.035f, 0.04f});

    void line(int x0, int y0, int x1, int y1, const PlotColour& c);
    void thickLine(int x0, int y0, int x1, int y1, const PlotColour& c); // 3 pixels wide
    void dashed(int x0, int y0, int x1, int y1, const PlotColour& c);
    void box(int x0, int y0, int x1, int y1, const PlotColour& c, bool fill);
    void text(int x, int y, const std::string& s, int size, const PlotColour& c,
              OIIO::ImageBufAlgo::TextAlignX ax = OIIO::ImageBufAlgo::TextAlignX::Left,
              OIIO::ImageBufAlgo::TextAlignY ay = OIIO::ImageBufAlgo::TextAlignY::Baseline);

    Image image() const; // the canvas as an RGB float image (writeImage saves it)
};

// printf-style formatting of one number, for tick labels.
std::string plotNumber(const char* format, double v);

} // namespace specula
