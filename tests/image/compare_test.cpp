#include "engine/core/error.h"
#include "engine/image_io/compare.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace specula {
namespace {

Image randomImage(int w, int h, int channels, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(0.f, 1.f);
    Image img(w, h, channels);
    for (float& v : img.pixels)
        v = dist(rng);
    return img;
}

struct Direct {
    double rmse = 0, mean = 0, max = 0, fractionOver = 0;
    std::size_t pixels = 0;
};

// The statistics written out longhand, one pixel at a time.
Direct directStats(const Image& a, const Image& b, const Image* mask, float threshold) {
    Direct d;
    double sq = 0, abs = 0;
    std::size_t over = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (mask && !(mask->at(x, y)[0] > 0.5f)) continue;
            ++d.pixels;
            bool isOver = false;
            for (int c = 0; c < 3; ++c) {
                const double e = std::fabs(double(a.at(x, y)[c]) - double(b.at(x, y)[c]));
                sq += e * e;
                abs += e;
                d.max = std::max(d.max, e);
                isOver = isOver || e > threshold;
            }
            over += isOver ? 1 : 0;
        }
    d.rmse = std::sqrt(sq / double(d.pixels * 3));
    d.mean = abs / double(d.pixels * 3);
    d.fractionOver = double(over) / double(d.pixels);
    return d;
}

TEST(CompareImages, IdenticalImagesGiveInfinitePsnr) {
    const Image a = randomImage(16, 9, 4, 1);
    const ImageStats s = compareImages(a, a);
    EXPECT_EQ(s.rmse, 0.0);
    EXPECT_EQ(s.maxError, 0.0);
    EXPECT_EQ(s.fractionOver, 0.0);
    EXPECT_EQ(s.pixels, 16u * 9u);
    EXPECT_TRUE(s.hasPsnr);
    EXPECT_TRUE(std::isinf(s.psnr) && s.psnr > 0);
    EXPECT_EQ(formatPsnr(s.psnr), "inf");
}

TEST(CompareImages, UnmaskedMatchesHandComputation) {
    const Image a = randomImage(17, 11, 3, 2);
    const Image b = randomImage(17, 11, 3, 3);
    const ImageStats s = compareImages(a, b, nullptr, 0.3f);
    const Direct d = directStats(a, b, nullptr, 0.3f);
    EXPECT_EQ(s.pixels, d.pixels);
    EXPECT_NEAR(s.rmse, d.rmse, 1e-6);
    EXPECT_NEAR(s.meanError, d.mean, 1e-6);
    EXPECT_NEAR(s.maxError, d.max, 1e-6);
    EXPECT_NEAR(s.fractionOver, d.fractionOver, 1e-12);
    EXPECT_NEAR(s.psnr, 20.0 * std::log10(1.0 / d.rmse), 1e-4);
}

TEST(CompareImages, MaskedMatchesHandComputation) {
    const Image a = randomImage(23, 13, 4, 4);
    Image b = randomImage(23, 13, 4, 5);
    Image mask = randomImage(23, 13, 1, 6); // about half the pixels over 0.5
    // Huge differences outside the mask must not leak in.
    for (int y = 0; y < 13; ++y)
        for (int x = 0; x < 23; ++x)
            if (!(mask.at(x, y)[0] > 0.5f)) b.at(x, y)[0] = 100.f;
    // Alpha differences are ignored.
    b.at(0, 0)[3] = 50.f;
    const ImageStats s = compareImages(a, b, &mask, 0.4f);
    const Direct d = directStats(a, b, &mask, 0.4f);
    ASSERT_GT(d.pixels, 0u);
    ASSERT_LT(d.pixels, 23u * 13u);
    EXPECT_EQ(s.pixels, d.pixels);
    EXPECT_NEAR(s.rmse, d.rmse, 1e-6);
    EXPECT_NEAR(s.meanError, d.mean, 1e-6);
    EXPECT_NEAR(s.maxError, d.max, 1e-6);
    EXPECT_NEAR(s.fractionOver, d.fractionOver, 1e-12);
    EXPECT_NEAR(s.psnr, 20.0 * std::log10(1.0 / d.rmse), 1e-4);
}

TEST(CompareImages, EmptyMaskComparesNothing) {
    const Image a = randomImage(5, 5, 3, 7);
    const Image b = randomImage(5, 5, 3, 8);
    const Image mask(5, 5, 1);
    const ImageStats s = compareImages(a, b, &mask);
    EXPECT_EQ(s.pixels, 0u);
    EXPECT_EQ(s.rmse, 0.0);
    // No reflector pixel: no PSNR at all, not +inf (which read as a perfect frame).
    EXPECT_FALSE(s.hasPsnr);
    EXPECT_TRUE(std::isnan(s.psnr));
    EXPECT_EQ(formatPsnr(s.psnr), "none");
}

TEST(CompareImages, TwoBlackFramesHaveNoPsnr) {
    // A scene with nothing to reflect: truth and render both black on the reflector. Equal,
    // but nothing was measured; +inf here scored broken scenes as perfect.
    const Image a(6, 4, 3), b(6, 4, 3);
    Image mask(6, 4, 1);
    mask.at(2, 1)[0] = mask.at(3, 2)[0] = 1.f;
    const ImageStats s = compareImages(a, b, &mask);
    EXPECT_EQ(s.pixels, 2u);
    EXPECT_FALSE(s.hasPsnr);
    EXPECT_TRUE(std::isnan(s.psnr));
    // Signal outside the mask does not count as measured.
    Image lit = a;
    lit.at(0, 0)[0] = 1.f;
    EXPECT_FALSE(compareImages(lit, lit, &mask).hasPsnr);
}

TEST(CompareImages, BlackFrameAgainstLitTruthScoresLow) {
    // Reflector pixels all black where the truth shows the room: a low score, its RMSE the
    // truth's own RMS.
    Image truth = randomImage(12, 8, 3, 9);
    for (float& v : truth.pixels)
        v = 0.2f + 0.6f * v;
    const Image black(12, 8, 3);
    const ImageStats s = compareImages(black, truth);
    ASSERT_TRUE(s.hasPsnr);
    EXPECT_LT(s.psnr, 12.0);
    double sq = 0;
    for (float v : truth.pixels)
        sq += double(v) * v;
    EXPECT_NEAR(s.rmse, std::sqrt(sq / double(truth.pixels.size())), 1e-6);
    // And the other way round: a black truth and a lit render is a real error too.
    EXPECT_LT(compareImages(truth, black).psnr, 12.0);
}

TEST(CompareImages, NonFiniteValueAnywhereIsAnError) {
    const Image a = randomImage(7, 5, 4, 10);
    Image mask(7, 5, 1);
    mask.at(1, 1)[0] = 1.f;
    for (float bad :
         {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        for (bool inMask : {true, false}) {
            Image b = a;
            b.at(inMask ? 1 : 5, inMask ? 1 : 3)[1] = bad;
            EXPECT_THROW(compareImages(a, b, &mask), Error) << bad << " " << inMask;
            EXPECT_THROW(compareImages(b, a, &mask), Error) << bad << " " << inMask;
        }
    }
    // Alpha is not measured: a NaN there is not an error.
    Image b = a;
    b.at(3, 3)[3] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NO_THROW(compareImages(a, b, &mask));
}

TEST(FormatPsnr, NoneInfAndDigits) {
    EXPECT_EQ(formatPsnr(std::numeric_limits<double>::quiet_NaN()), "none");
    EXPECT_EQ(formatPsnr(std::numeric_limits<double>::infinity()), "inf");
    EXPECT_EQ(formatPsnr(31.4159, 2), "31.42");
    EXPECT_EQ(formatPsnr(-3.5, 1), "-3.5");
}

TEST(CompareImages, SizeMismatchThrows) {
    EXPECT_THROW(compareImages(Image(4, 4, 3), Image(4, 5, 3)), Error);
    const Image mask(3, 3, 1);
    EXPECT_THROW(compareImages(Image(4, 4, 3), Image(4, 4, 3), &mask), Error);
}

TEST(ErrorHeatmap, RampAndMask) {
    Image a(3, 1, 3), b(3, 1, 3);
    b.at(1, 0)[1] = 0.1f; // full scale
    Image mask(3, 1, 1);
    mask.at(0, 0)[0] = mask.at(1, 0)[0] = 1.f;
    const Image h = errorHeatmap(a, b, &mask, 0.1f);
    ASSERT_EQ(h.channels, 3);
    // No error: the dark blue end; full error: the red end; masked out: neutral grey.
    EXPECT_GT(h.at(0, 0)[2], h.at(0, 0)[0]);
    EXPECT_GT(h.at(1, 0)[0], h.at(1, 0)[1]);
    EXPECT_GT(h.at(1, 0)[0], h.at(1, 0)[2]);
    EXPECT_FLOAT_EQ(h.at(2, 0)[0], h.at(2, 0)[1]);
    EXPECT_FLOAT_EQ(h.at(2, 0)[1], h.at(2, 0)[2]);
}

TEST(ErodedMask, KeepsTheInteriorOnly) {
    // A 4x3 block in a 6x5 mask: only its two middle pixels have a full 3x3 neighbourhood.
    Image mask(6, 5, 1);
    for (int y = 1; y <= 3; ++y)
        for (int x = 1; x <= 4; ++x)
            mask.at(x, y)[0] = 1.f;
    const Image e = erodedMask(mask);
    ASSERT_EQ(e.channels, 1);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 6; ++x)
            EXPECT_EQ(e.at(x, y)[0], y == 2 && (x == 2 || x == 3) ? 1.f : 0.f) << x << "," << y;
    // The image border counts as outside: an all-mask image keeps its inner pixels only.
    Image full(3, 3, 1);
    for (float& v : full.pixels)
        v = 1.f;
    const Image f = erodedMask(full);
    EXPECT_EQ(f.at(1, 1)[0], 1.f);
    EXPECT_EQ(f.at(0, 1)[0], 0.f);
}

} // namespace
} // namespace specula
