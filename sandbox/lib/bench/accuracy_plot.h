#pragma once
// accuracy_vs_time.png: one panel per scene, PSNR (reflector pixels, environment-only ground
// truth) against the reflector-pass time as a ratio to envmap (log2 axis). Each method's
// sweep is a connected line in its own colour; the Pareto front (no other row is both
// faster and more accurate) is ringed in white and joined by a dashed line. Drawn with
// OpenImageIO's render_line / render_box / render_text.
#include "engine/image/image.h"

#include <string>
#include <vector>

namespace specula {

struct PlotPoint {
    std::string method; // one line per method, in order of appearance
    std::string label;  // e.g. "d_e=0.01"
    double ratio = 1.0; // time / envmap time
    double psnr = 0.0;  // dB; NaN (nothing measured) and inf are left out, never drawn
};

struct PlotPanel {
    std::string title;
    std::vector<PlotPoint> points;
};

// Indices of the points on the Pareto front (minimal ratio, maximal PSNR), by ratio.
std::vector<std::size_t> paretoFront(const std::vector<PlotPoint>& points);

Image accuracyPlot(const std::vector<PlotPanel>& panels, int panelWidth = 640,
                   int panelHeight = 480);

} // namespace specula
