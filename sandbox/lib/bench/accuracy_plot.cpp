#include "sandbox/lib/bench/accuracy_plot.h"

#include "engine/image/plot_canvas.h"
#include "sandbox/lib/bench/bench_methods.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace specula {

namespace {

// One colour per method, the same in every panel: the flavours' method tables give it; a
// method they do not list gets grey.
std::array<float, 3> methodColour(const std::string& method) {
    for (const MethodLabel& m : sandboxMethods())
        if (method == m.name) return m.colour;
    return {0.60f, 0.60f, 0.60f};
}

void drawPanel(PlotCanvas& cv, int ox, int pw, int ph, const PlotPanel& panel) {
    using OIIO::ImageBufAlgo::TextAlignX;
    using OIIO::ImageBufAlgo::TextAlignY;
    const std::array<float, 3> axis{0.8f, 0.8f, 0.8f}, grid{0.07f, 0.07f, 0.08f},
        white{1.f, 1.f, 1.f};
    const int left = ox + 64, right = ox + pw - 20, top = 58, bottom = ph - 52;

    std::vector<PlotPoint> pts;
    for (const PlotPoint& p : panel.points)
        if (std::isfinite(p.psnr) && std::isfinite(p.ratio) && p.ratio > 0) pts.push_back(p);
    double rMin = 1, rMax = 2, pMin = 0, pMax = 1;
    if (!pts.empty()) {
        rMin = rMax = pts[0].ratio;
        pMin = pMax = pts[0].psnr;
        for (const PlotPoint& p : pts) {
            rMin = std::min(rMin, p.ratio), rMax = std::max(rMax, p.ratio);
            pMin = std::min(pMin, p.psnr), pMax = std::max(pMax, p.psnr);
        }
    }
    // x: log2 of the ratio, whole powers of two as ticks; y: PSNR, 5 dB ticks.
    double lx0 = std::floor(std::log2(rMin) - 0.25), lx1 = std::ceil(std::log2(rMax) + 0.25);
    if (lx1 - lx0 < 2) lx1 = lx0 + 2;
    double y0 = std::floor(pMin / 5.0) * 5.0 - 2.5, y1 = std::ceil(pMax / 5.0) * 5.0 + 2.5;
    auto X = [&](double r) {
        return int(left + (std::log2(r) - lx0) / (lx1 - lx0) * (right - left));
    };
    auto Y = [&](double p) { return int(bottom - (p - y0) / (y1 - y0) * (bottom - top)); };

    for (double l = lx0; l <= lx1 + 1e-9; l += 1) {
        const int x = X(std::exp2(l));
        cv.line(x, top, x, bottom, grid);
        cv.line(x, bottom, x, bottom + 5, axis);
        cv.text(x, bottom + 20, plotNumber(l >= 0 ? "%.0f" : "%.3g", std::exp2(l)), 13, axis,
                TextAlignX::Center);
    }
    for (double v = std::ceil(y0 / 5.0) * 5.0; v <= y1; v += 5) {
        const int y = Y(v);
        cv.line(left, y, right, y, grid);
        cv.line(left - 5, y, left, y, axis);
        cv.text(left - 8, y + 5, plotNumber("%.0f", v), 13, axis, TextAlignX::Right);
    }
    cv.box(left, top, right, bottom, axis, false);
    cv.text((left + right) / 2, ph - 12, "reflector pass time / envmap (log scale)", 14, axis,
            TextAlignX::Center);
    cv.text(ox + 14, top - 10, "PSNR dB (reflector pixels, env-only ground truth)", 13, axis);
    cv.text((left + right) / 2, 24, panel.title, 17, white, TextAlignX::Center);

    // Lines per method, then the points, then the Pareto front on top.
    std::map<std::string, std::array<float, 3>> colourOf;
    std::vector<std::string> order;
    for (const PlotPoint& p : pts)
        if (colourOf.emplace(p.method, methodColour(p.method)).second) order.push_back(p.method);
    for (const std::string& m : order) {
        std::vector<const PlotPoint*> line;
        for (const PlotPoint& p : pts)
            if (p.method == m) line.push_back(&p);
        std::sort(line.begin(), line.end(), [](auto* a, auto* b) { return a->ratio < b->ratio; });
        const std::array<float, 3>& c = colourOf[m];
        for (std::size_t i = 1; i < line.size(); ++i)
            cv.thickLine(X(line[i - 1]->ratio), Y(line[i - 1]->psnr), X(line[i]->ratio),
                         Y(line[i]->psnr), c);
        for (const PlotPoint* p : line)
            cv.box(X(p->ratio) - 4, Y(p->psnr) - 4, X(p->ratio) + 4, Y(p->psnr) + 4, c, true);
    }
    const std::vector<std::size_t> front = paretoFront(pts);
    for (std::size_t i = 0; i < front.size(); ++i) {
        const PlotPoint& p = pts[front[i]];
        cv.box(X(p.ratio) - 8, Y(p.psnr) - 8, X(p.ratio) + 8, Y(p.psnr) + 8, white, false);
        if (i > 0) {
            const PlotPoint& q = pts[front[i - 1]];
            cv.dashed(X(q.ratio), Y(q.psnr), X(p.ratio), Y(p.psnr), white);
        }
    }
    // Legend, bottom right inside the frame.
    int ly = bottom - 14 - 18 * int(order.size());
    for (const std::string& m : order) {
        const std::array<float, 3>& c = colourOf[m];
        cv.box(right - 130, ly - 9, right - 118, ly + 1, c, true);
        cv.text(right - 112, ly, m, 13, axis);
        ly += 18;
    }
    cv.box(right - 132, ly - 10, right - 116, ly + 2, white, false);
    cv.text(right - 112, ly, "Pareto front", 13, axis);
}

} // namespace

std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points) {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const PlotPoint& p = points[i];
        if (!std::isfinite(p.psnr) || !std::isfinite(p.ratio)) continue;
        bool dominated = false;
        for (std::size_t j = 0; j < points.size() && !dominated; ++j) {
            const PlotPoint& q = points[j];
            if (j == i || !std::isfinite(q.psnr) || !std::isfinite(q.ratio)) continue;
            dominated =
                q.ratio <= p.ratio && q.psnr >= p.psnr && (q.ratio < p.ratio || q.psnr > p.psnr);
        }
        if (!dominated) idx.push_back(i);
    }
    std::sort(idx.begin(), idx.end(),
              [&](std::size_t a, std::size_t b) { return points[a].ratio < points[b].ratio; });
    return idx;
}

Image accuracyPlot(const std::vector<PlotPanel>& panels, int pw, int ph) {
    const int n = std::max<int>(1, int(panels.size()));
    PlotCanvas cv(pw * n, ph);
    for (int i = 0; i < int(panels.size()); ++i)
        drawPanel(cv, i * pw, pw, ph, panels[std::size_t(i)]);
    return cv.image();
}

} // namespace specula
