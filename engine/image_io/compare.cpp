#include "engine/image_io/compare.h"

#include "engine/core/error.h"
#include "engine/image_io/image_io.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace specula {

namespace {

int comparedChannels(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        throw Error("", "image size",
                    "images differ in size: " + std::to_string(a.width) + "x" +
                        std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" +
                        std::to_string(b.height));
    if (a.channels >= 3 && b.channels >= 3) return 3;
    if (a.channels != b.channels)
        throw Error("", "image channels",
                    "cannot compare " + std::to_string(a.channels) + " with " +
                        std::to_string(b.channels) + " channels");
    return a.channels;
}

void checkMask(const Image& a, const Image* mask) {
    if (mask && (mask->width != a.width || mask->height != a.height || mask->channels < 1))
        throw Error("", "mask", "mask size differs from the compared images");
}

// Non-finite values make every statistic meaningless (OIIO would fold a NaN into the sums),
// so they are refused wherever they sit, naming the first one.
void checkFinite(const Image& img, int channels, const char* which) {
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < channels; ++c)
                if (!std::isfinite(img.at(x, y)[c]))
                    throw Error("", std::string(which) + " image",
                                "pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                    ") channel " + std::to_string(c) + " is " +
                                    (std::isnan(img.at(x, y)[c]) ? "NaN" : "infinite") +
                                    ": a measured image must hold finite values");
}

bool selected(const Image* mask, int x, int y) {
    return !mask || mask->at(x, y)[0] > 0.5f;
}

// The compared channels of `img` as an OIIO buffer, unselected pixels zero in both inputs so
// they contribute no difference (zeroed here rather than multiplied, so a NaN outside the
// mask cannot leak in).
OIIO::ImageBuf toBuf(const Image& img, int channels, const Image* mask) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(img.width, img.height, channels, OIIO::TypeDesc::FLOAT));
    std::vector<float> data(std::size_t(img.width) * img.height * channels, 0.f);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            if (!selected(mask, x, y)) continue;
            const float* p = img.at(x, y);
            std::copy(p, p + channels, &data[(std::size_t(y) * img.width + x) * channels]);
        }
    buf.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, data.data());
    return buf;
}

// Whether any compared value of the selected pixels is non-zero (the images are equal here,
// so one image answers for both).
bool anySignal(const Image& img, int channels, const Image* mask) {
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (selected(mask, x, y))
                for (int c = 0; c < channels; ++c)
                    if (img.at(x, y)[c] != 0.f) return true;
    return false;
}

} // namespace

ImageStats compareImages(const Image& a, const Image& b, const Image* mask, float threshold) {
    const int channels = comparedChannels(a, b);
    checkMask(a, mask);
    checkFinite(a, channels, "first");
    checkFinite(b, channels, "second");
    const std::size_t total = std::size_t(a.width) * a.height;
    std::size_t count = total;
    if (mask) {
        count = 0;
        for (int y = 0; y < a.height; ++y)
            for (int x = 0; x < a.width; ++x)
                count += selected(mask, x, y) ? 1 : 0;
    }
    ImageStats s;
    s.pixels = count;
    s.psnr = std::numeric_limits<double>::quiet_NaN();
    if (count == 0) return s;
    const OIIO::ImageBuf ba = toBuf(a, channels, mask);
    const OIIO::ImageBuf bb = toBuf(b, channels, mask);
    const OIIO::ImageBufAlgo::CompareResults r =
        OIIO::ImageBufAlgo::compare(ba, bb, threshold, threshold);
    // OIIO sets `error` whenever a pixel fails the threshold too; only a failure with no
    // failing pixel is a real error.
    if (r.error && r.nfail == 0 && r.nwarn == 0)
        throw Error("", "", "image comparison failed: " + OIIO::geterror());
    // OIIO averages over every pixel of the buffers; the zeroed ones add nothing to the
    // sums, so rescale from all pixels to the selected ones.
    const double scale = double(total) / double(count);
    s.rmse = std::sqrt(r.rms_error * r.rms_error * scale);
    s.meanError = r.meanerror * scale;
    s.maxError = r.maxerror;
    s.fractionOver = double(r.nfail) / double(count);
    if (s.rmse > 0.0) {
        s.hasPsnr = true;
        s.psnr = 20.0 * std::log10(1.0 / s.rmse);
    } else if (anySignal(a, channels, mask)) {
        s.hasPsnr = true;
        s.psnr = std::numeric_limits<double>::infinity();
    }
    return s;
}

std::string formatPsnr(double psnr, int decimals) {
    if (std::isnan(psnr)) return "none";
    if (std::isinf(psnr)) return psnr > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*f", decimals, psnr);
    return buf;
}

double meanPsnr(std::span<const double> psnrs) {
    double sum = 0.0;
    std::size_t n = 0;
    for (const double p : psnrs)
        if (!std::isnan(p)) sum += p, ++n;
    return n ? sum / double(n) : std::numeric_limits<double>::quiet_NaN();
}

double worstPsnr(std::span<const double> psnrs) {
    double worst = std::numeric_limits<double>::quiet_NaN();
    for (const double p : psnrs)
        if (!std::isnan(p) && !(p >= worst)) worst = p;
    return worst;
}

Image errorHeatmap(const Image& a, const Image& b, const Image* mask, float maxError) {
    const int channels = comparedChannels(a, b);
    checkMask(a, mask);
    // Stops are display colours (sRGB-encoded), converted to linear at the end so the
    // written PNG shows them as chosen.
    static constexpr std::array<std::array<float, 3>, 5> kRamp{{{0.05f, 0.05f, 0.30f},
                                                                {0.10f, 0.45f, 0.95f},
                                                                {0.15f, 0.80f, 0.30f},
                                                                {0.98f, 0.90f, 0.15f},
                                                                {0.90f, 0.10f, 0.10f}}};
    const float grey = srgbToLinearValue(0.5f);
    Image out(a.width, a.height, 3);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            float* o = out.at(x, y);
            if (!selected(mask, x, y)) {
                o[0] = o[1] = o[2] = grey;
                continue;
            }
            float e = 0.f;
            for (int c = 0; c < channels; ++c) {
                const float d = std::fabs(a.at(x, y)[c] - b.at(x, y)[c]);
                e = std::isnan(d) ? std::numeric_limits<float>::infinity() : std::max(e, d);
            }
            float t = maxError > 0.f ? e / maxError : (e > 0.f ? 1.f : 0.f);
            t = std::clamp(t, 0.f, 1.f) * float(kRamp.size() - 1);
            const int i = std::min(int(t), int(kRamp.size()) - 2);
            const float f = t - float(i);
            for (int c = 0; c < 3; ++c)
                o[c] = srgbToLinearValue(kRamp[i][c] + (kRamp[i + 1][c] - kRamp[i][c]) * f);
        }
    return out;
}

Image erodedMask(const Image& mask) {
    Image out(mask.width, mask.height, 1);
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            bool all = true;
            for (int dy = -1; dy <= 1 && all; ++dy)
                for (int dx = -1; dx <= 1 && all; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    all = xx >= 0 && yy >= 0 && xx < mask.width && yy < mask.height &&
                          mask.at(xx, yy)[0] > 0.5f;
                }
            out.at(x, y)[0] = all ? 1.f : 0.f;
        }
    return out;
}

} // namespace specula
