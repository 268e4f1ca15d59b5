#pragma once
// Image comparison for the accuracy reports: RGB only, optionally restricted to a mask
// (the reflector pixels). Statistics come from OpenImageIO's ImageBufAlgo::compare.
#include "engine/image/image.h"

#include <cstddef>
#include <span>
#include <string>

namespace specula {

struct ImageStats {
    double rmse = 0.0; // over RGB values of the compared pixels
    // PSNR in dB, peak 1.0, only where something was measured (hasPsnr):
    //  - no pixel compared (an empty mask: the camera sees no reflector) -> no PSNR;
    //  - every compared value zero in both images (two black frames: a scene with nothing to
    //    reflect agrees with any black render) -> no PSNR, since calling that perfect would
    //    score a broken setup as flawless;
    //  - +inf only when there is signal and every compared value matches exactly (the truth
    //    compared with itself), which is honest: the error is zero.
    // Without a PSNR, psnr is NaN so no caller can mistake it for a score; print it with
    // formatPsnr. A black frame against a truth that is not black scores low like any other
    // error (its RMSE is the truth's own RMS).
    bool hasPsnr = false;
    double psnr = 0.0;
    double maxError = 0.0;     // largest absolute channel difference
    double meanError = 0.0;    // mean absolute channel difference
    std::size_t pixels = 0;    // pixels compared (mask pixels, or all)
    double fractionOver = 0.0; // share of compared pixels with any channel over threshold
};

// Compares the RGB channels of a and b (same size, at least 3 channels, or the same channel
// count when fewer). mask: only pixels whose channel 0 is > 0.5 count; when it selects no
// pixel, the result has pixels = 0, all errors 0 and no PSNR. Throws Error on size or
// channel mismatch, and when a compared channel of either image is NaN or infinite anywhere
// (masked out or not): a measured image holding a non-number is broken, not scoreable.
ImageStats compareImages(const Image& a, const Image& b, const Image* mask = nullptr,
                         float threshold = 0.05f);

// A PSNR as the reports print it: "none" when there is none (NaN), "inf" for an exact match,
// else fixed-point with `decimals` digits.
std::string formatPsnr(double psnr, int decimals = 2);

// The mean and the worst (lowest) of the PSNRs that exist: a NaN (nothing measured, see
// ImageStats) is left out, never averaged in as some number of dB; NaN when none exists.
double meanPsnr(std::span<const double> psnrs);
double worstPsnr(std::span<const double> psnrs);

// Per-pixel error (largest absolute RGB difference) mapped to a colour ramp from dark blue
// (0) through green and yellow to red (>= maxError); masked-out pixels are grey. Returns
// linear RGB, ready for writeImage.
Image errorHeatmap(const Image& a, const Image& b, const Image* mask, float maxError);

// The pixels of a 1-channel mask (channel 0 > 0.5) whose 3x3 neighbourhood lies inside the
// image and is all mask: two renderers may disagree on which silhouette pixels an object
// covers, never on its interior.
Image erodedMask(const Image& mask);

} // namespace specula
