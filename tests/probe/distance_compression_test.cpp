// The compressed form of a distance probe (distance_compression.h) against closed forms: its
// bytes per cube, and the asset the round trip leaves: radiance within BC6H's error of the
// original (the codec's own tests hold its blocks to the GL driver's decode) and distances
// exactly the half floats an R16F texture holds.
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "probe/analytic_probe.h"

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

TEST(DistanceCompression, TheRoundTripKeepsRadianceNearAndDistancesAsHalves) {
    const DistanceProbeAsset original = test::makeBoxProbe(test::AnalyticBox{}, 16);
    DistanceProbeAsset compressed = original;
    ASSERT_TRUE(allLayersFitHalf(original));
    roundTripLayersThroughBc6h(compressed);
    double worstRelative = 0;
    bool radianceChanged = false;
    for (std::size_t L = 0; L < original.layers.size(); ++L)
        for (std::size_t f = 0; f < 6; ++f) {
            const Image& a = original.layers[L].faces[f];
            const Image& b = compressed.layers[L].faces[f];
            for (std::size_t t = 0; t < a.pixels.size(); t += 4) {
                for (std::size_t c = 0; c < 3; ++c) {
                    const double rel = std::abs(double(b.pixels[t + c]) - a.pixels[t + c]) /
                                       std::max(1e-3, double(a.pixels[t + c]));
                    worstRelative = std::max(worstRelative, rel);
                    radianceChanged |= b.pixels[t + c] != a.pixels[t + c];
                }
                EXPECT_EQ(b.pixels[t + 3], roundToHalf(a.pixels[t + 3]));
            }
        }
    std::printf("[bc6h-probe] worst relative radiance error %.4f\n", worstRelative);
    EXPECT_TRUE(radianceChanged); // the blocks are lossy: a no-op would pass the bound too
    EXPECT_LT(worstRelative, 0.05);
}

} // namespace
} // namespace specula
