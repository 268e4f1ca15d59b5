#pragma once
// A synthetic HDR image with what a cooked probe face holds, for texture codecs: a smooth sky
// from 0.05 to 2, a sun of 5000 with a soft rim, lit walls of 20 to 60 with sharp edges,
// and fine texture noise of a few percent; and the measures a codec is held to.
#include "engine/image/image.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace specula::test {

inline Image hdrTestImage(int width, int height, std::uint32_t seed = 1) {
    Image img(width, height, 3);
    std::uint32_t state = seed * 747796405u + 2891336453u;
    const auto noise = [&state] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) / float(1u << 24) - 0.5f;
    };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float u = (float(x) + 0.5f) / float(width), v = (float(y) + 0.5f) / float(height);
            float r = 0.05f + 1.95f * (1.f - v) * (1.f - v), g = r * 1.1f, b = r * 1.5f;
            const float sun = std::hypot(u - 0.7f, v - 0.2f);
            if (sun < 0.03f)
                r = g = b = 5000.f;
            else if (sun < 0.08f) {
                const float rim = 200.f * std::exp(-60.f * (sun - 0.03f));
                r += rim, g += 0.8f * rim, b += 0.5f * rim;
            }
            if (u > 0.1f && u < 0.4f && v > 0.5f && v < 0.9f) { // a lit wall, striped
                const float stripe = (int(u * 40.f) % 2) ? 60.f : 20.f;
                r = stripe, g = 0.9f * stripe, b = 0.7f * stripe;
            }
            const float n = 1.f + 0.04f * noise();
            float* p = img.at(x, y);
            p[0] = r * n, p[1] = g * n, p[2] = b * n;
        }
    return img;
}

// PSNR of log2 luminance (the measure an HDR codec is usually held to): the peak is the
// reference's log2 dynamic range, luminance floored at 1e-3.
inline double logLuminancePsnr(const Image& ref, const Image& test) {
    const auto logLum = [](const float* p) {
        return std::log2(std::max(1e-3, 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]));
    };
    double lo = 1e30, hi = -1e30, mse = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x) {
            const double a = logLum(ref.at(x, y)), d = a - logLum(test.at(x, y));
            lo = std::min(lo, a), hi = std::max(hi, a), mse += d * d;
        }
    mse /= double(ref.width) * ref.height;
    return mse > 0 ? 10.0 * std::log10((hi - lo) * (hi - lo) / mse) : 99.0;
}

// PSNR of the RGB values with the reference's largest value as the peak.
inline double linearPsnr(const Image& ref, const Image& test) {
    double peak = 0, mse = 0;
    for (int y = 0; y < ref.height; ++y)
        for (int x = 0; x < ref.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double a = ref.at(x, y)[c], d = a - test.at(x, y)[c];
                peak = std::max(peak, a), mse += d * d;
            }
    mse /= 3.0 * ref.width * ref.height;
    return mse > 0 ? 10.0 * std::log10(peak * peak / mse) : 99.0;
}

} // namespace specula::test
