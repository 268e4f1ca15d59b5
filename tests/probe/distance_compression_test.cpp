// The compressed form of a distance probe (distance_compression.h) against closed forms: its
// bytes per cube, and the asset the round trip leaves: radiance exactly each face's BC6H blocks
// decoded (the codec's own tests hold its blocks to the GL driver's decode and to a quality
// floor) and distances exactly the half floats an R16F texture holds.
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "engine/image/bc6h.h"
#include "probe/analytic_probe.h"
#include "support/hdr_test_image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace specula {
namespace {

TEST(DistanceCompression, BytesPerCubeAreTheFormatsClosedForms) {
    const std::size_t texels = 6 * 256 * 256;
    EXPECT_EQ(cubeBytesRgba32f(256), texels * 16);
    EXPECT_EQ(cubeBytesRgba16f(256), texels * 8);
    EXPECT_EQ(cubeBytesBc6hR16f(256), texels * 1 + texels * 2); // 1.125 MiB
    // A face of 6 texels pads to 2 x 2 blocks for the radiance; the distance does not pad.
    EXPECT_EQ(cubeBytesBc6hR16f(6), 6u * (4 * 16 + 36 * 2));
}

TEST(DistanceCompression, TheRoundTripHoldsTheDecodedBlocksAndHalfDistances) {
    const DistanceProbeAsset original = test::makeBoxProbe(test::AnalyticBox{}, 16);
    DistanceProbeAsset compressed = original;
    ASSERT_TRUE(allLayersFitHalf(original));
    roundTripLayersThroughBc6h(compressed);
    // Radiance as one RGB strip of every face, to measure like the codec's own tests.
    const auto strip = [](const DistanceProbeAsset& a) {
        const int n = a.faceRes;
        Image s(n, 6 * n * int(a.layers.size()), 3);
        for (std::size_t L = 0; L < a.layers.size(); ++L)
            for (int f = 0; f < 6; ++f)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x)
                        std::copy(a.layers[L].faces[std::size_t(f)].at(x, y),
                                  a.layers[L].faces[std::size_t(f)].at(x, y) + 3,
                                  s.at(x, (int(L) * 6 + f) * n + y));
        return s;
    };
    const Image before = strip(original), after = strip(compressed);
    EXPECT_NE(before.pixels, after.pixels); // the blocks are lossy: a no-op would pass too
    // A figure, not a floor: this box's three channels vary independently within a 4x4 block
    // (sines of different directions), the case a one-region encoder fits worst. The codec's
    // floor on HDR content is tests/image/bc6h_test.cpp's.
    std::printf("[bc6h-probe] analytic box 16^2: log-luminance PSNR %.2f dB, linear %.2f dB\n",
                test::logLuminancePsnr(before, after), test::linearPsnr(before, after));
    // Each face's radiance is exactly its blocks decoded: the asset is what a reader of the
    // compressed probe sees.
    for (std::size_t L = 0; L < original.layers.size(); ++L)
        for (std::size_t f = 0; f < 6; ++f) {
            const Image& face = original.layers[L].faces[f];
            const Image decoded = decodeBC6H(encodeBC6H(face), face.width, face.height);
            const Image& got = compressed.layers[L].faces[f];
            for (std::size_t t = 0; t < std::size_t(face.width) * std::size_t(face.height); ++t)
                for (std::size_t c = 0; c < 3; ++c)
                    ASSERT_EQ(got.pixels[4 * t + c], decoded.pixels[3 * t + c])
                        << "layer " << L << " face " << f << " texel " << t;
        }
    for (std::size_t L = 0; L < original.layers.size(); ++L)
        for (std::size_t f = 0; f < 6; ++f) {
            const Image& a = original.layers[L].faces[f];
            const Image& b = compressed.layers[L].faces[f];
            for (std::size_t t = 3; t < a.pixels.size(); t += 4)
                ASSERT_EQ(b.pixels[t], roundToHalf(a.pixels[t])) << "layer " << L << " face " << f;
        }
}

} // namespace
} // namespace specula
