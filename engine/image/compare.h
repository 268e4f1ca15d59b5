#pragma once
// Image comparison for the accuracy reports: RGB only, optionally restricted to a mask
// (the reflector pixels). Statistics come from OpenImageIO's ImageBufAlgo::compare.
#include "engine/image/image.h"

#include <cstddef>

namespace specula {

struct ImageStats {
    double rmse = 0.0;         // over RGB values of the compared pixels
    double psnr = 0.0;         // peak 1.0; +inf when identical (callers cap for display)
    double maxError = 0.0;     // largest absolute channel difference
    double meanError = 0.0;    // mean absolute channel difference
    std::size_t pixels = 0;    // pixels compared (mask pixels, or all)
    double fractionOver = 0.0; // share of compared pixels with any channel over threshold
};

// Compares the RGB channels of a and b (same size, at least 3 channels, or the same channel
// count when fewer). mask: only pixels whose channel 0 is > 0.5 count; when it selects no
// pixel, the result has pixels = 0, all errors 0 and psnr +inf. Throws Error on size or
// channel mismatch.
ImageStats compareImages(const Image& a, const Image& b, const Image* mask = nullptr,
                         float threshold = 0.05f);

// Per-pixel error (largest absolute RGB difference) mapped to a colour ramp from dark blue
// (0) through green and yellow to red (>= maxError); masked-out pixels are grey. Returns
// linear RGB, ready for writeImage.
Image errorHeatmap(const Image& a, const Image& b, const Image* mask, float maxError);

} // namespace specula
