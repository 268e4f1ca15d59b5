// The light-field probe's glossy lookup (issue 14; shaders/lightfield_glossy.glsl.h) on its
// CPU twin: the mirror lookup untouched at roughness 0, the mips tile-local box filters, the
// filter exact on a uniform light field. Against brute-force GGX integrals:
// lightfield_glossy_ggx_test.cpp; the room's GGX truth and the shader: lightfield_glossy_test.cpp.
#include "components/reflection_probe/lightfield/lightfield_mips.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/image/bc1.h"
#include "engine/image/ggx_albedo.h"
#include "engine/image/srgb.h"
#include "lightfield_glossy_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <glm/glm.hpp>

using namespace specula;
using test::lf_glossy::Config;
using test::lf_glossy::emptyAsset;
using test::lf_glossy::maxAbs;
using test::lf_glossy::randomConfig;
using test::lf_glossy::srgbCode;

TEST(LightFieldGlossy, RoughnessZeroIsTheMirrorLookupBitForBit) {
    // Random texels, so any difference in arithmetic shows.
    LightFieldAsset a = emptyAsset(6, 32, 1.5f);
    std::mt19937 rng(14);
    std::uniform_int_distribution<int> byte(0, 255);
    for (auto& s : a.slabs)
        for (auto& b : s.data)
            b = std::uint8_t(byte(rng));
    const CpuLightFieldProbe lf(a);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int i = 0; i < 20000; ++i) {
        const Config c = randomConfig(rng, a.halfCell(), 0.f);
        const glm::vec3 want = lf.radiance(c.p, c.lhat);
        for (const float r : {0.f, -0.3f, nan}) {
            const glm::vec3 got = lf.glossyRadiance(c.p, c.lhat, c.n, r);
            const glm::vec3 shown = lf.reflectedRadiance(c.p, c.lhat, c.n, r);
            ASSERT_EQ(got.x, want.x) << "roughness " << r << ", ray " << i;
            ASSERT_EQ(got.y, want.y);
            ASSERT_EQ(got.z, want.z);
            ASSERT_EQ(shown, want);
        }
    }
}

TEST(LightFieldGlossy, MipsAreBoxAveragesWithinEachCameraTile) {
    EXPECT_EQ(lightFieldMaxLevel(64, LightFieldCompression::None), 6);
    EXPECT_EQ(lightFieldMaxLevel(64, LightFieldCompression::BC1), 4);
    EXPECT_EQ(lightFieldMaxLevel(48, LightFieldCompression::None), 4);
    EXPECT_EQ(lightFieldMaxLevel(48, LightFieldCompression::BC1), 2);
    EXPECT_EQ(lightFieldMaxLevel(4, LightFieldCompression::BC1), 0);
    // Random texels: level k must be the sRGB code of the linear mean of the 2^k x 2^k texels
    // of level 0 under it (the reference averages level 0 directly, not level by level), to
    // within one code (float summation order at a rounding boundary).
    LightFieldAsset a = emptyAsset(3, 16, 1.f);
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> byte(0, 255);
    for (auto& s : a.slabs)
        for (auto& b : s.data)
            b = std::uint8_t(byte(rng));
    const LightFieldMips mips = buildLightFieldMips(a);
    ASSERT_EQ(mips.maxLevel(), 4);
    const int n0 = a.atlasSize();
    int worst = 0;
    for (int k = 1; k <= mips.maxLevel(); ++k)
        for (int slab = 0; slab < 6; ++slab) {
            const auto& level = mips.levels[std::size_t(k - 1)][std::size_t(slab)];
            const int n = n0 >> k, side = 1 << k;
            ASSERT_EQ(level.size(), std::size_t(n) * std::size_t(n) * 3);
            const auto& base = a.slabs[std::size_t(slab)].data;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    for (int c = 0; c < 3; ++c) {
                        double sum = 0.0;
                        for (int yy = 0; yy < side; ++yy)
                            for (int xx = 0; xx < side; ++xx)
                                sum += srgbToLinearValue(
                                    float(base[(std::size_t(y * side + yy) * std::size_t(n0) +
                                                std::size_t(x * side + xx)) *
                                                   3 +
                                               std::size_t(c)]) /
                                    255.f);
                        const int want = srgbCode(float(sum / double(side * side)));
                        const int got =
                            level[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 3 +
                                  std::size_t(c)];
                        worst = std::max(worst, std::abs(got - want));
                    }
        }
    EXPECT_LE(worst, 1);
    // Each camera a flat colour of its own: no mip texel may mix two cameras, down to the
    // last level (one texel per camera). Exact: the mean of equal values is that value.
    LightFieldAsset flat = emptyAsset(4, 8, 1.f, LightFieldCompression::BC1);
    for (LightFieldCompression comp : {LightFieldCompression::None, LightFieldCompression::BC1}) {
        flat.compression = comp;
        auto cameraColour = [](int slab, int i, int j, int c) {
            return std::uint8_t((slab * 41 + i * 67 + j * 23 + c * 90) % 256);
        };
        const int n = flat.atlasSize();
        for (int slab = 0; slab < 6; ++slab) {
            std::vector<std::uint8_t> rgb(std::size_t(n) * std::size_t(n) * 3);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    for (int c = 0; c < 3; ++c)
                        rgb[(std::size_t(y) * std::size_t(n) + std::size_t(x)) * 3 +
                            std::size_t(c)] = cameraColour(slab, x / flat.res, y / flat.res, c);
            flat.slabs[std::size_t(slab)].data =
                comp == LightFieldCompression::BC1 ? encodeBC1(rgb.data(), n, n) : rgb;
        }
        const LightFieldMips m = buildLightFieldMips(flat);
        ASSERT_EQ(m.maxLevel(), comp == LightFieldCompression::BC1 ? 1 : 3);
        for (int k = 1; k <= m.maxLevel(); ++k)
            for (int slab = 0; slab < 6; ++slab) {
                const int nk = n >> k, tile = flat.res >> k;
                const auto& stored = m.levels[std::size_t(k - 1)][std::size_t(slab)];
                const std::vector<std::uint8_t> rgb =
                    comp == LightFieldCompression::BC1 ? decodeBC1(stored.data(), nk, nk) : stored;
                // BC1 stores 565 endpoints: a flat block decodes to its colour rounded to 565.
                const std::vector<std::uint8_t> level0 =
                    comp == LightFieldCompression::BC1
                        ? decodeBC1(flat.slabs[std::size_t(slab)].data.data(), n, n)
                        : flat.slabs[std::size_t(slab)].data;
                for (int y = 0; y < nk; ++y)
                    for (int x = 0; x < nk; ++x)
                        for (int c = 0; c < 3; ++c) {
                            const std::size_t at0 =
                                (std::size_t(y / tile * flat.res) * std::size_t(n) +
                                 std::size_t(x / tile * flat.res)) *
                                    3 +
                                std::size_t(c);
                            ASSERT_EQ(rgb[(std::size_t(y) * std::size_t(nk) + std::size_t(x)) * 3 +
                                          std::size_t(c)],
                                      level0[at0])
                                << toString(comp) << " level " << k << " slab " << slab;
                        }
            }
        // Level 1 of six 16^2 layers (and 8^2, 4^2 uncompressed): BC1 half a byte a texel,
        // RGB8 held as RGBA8.
        const std::size_t texels = std::size_t(n / 2) * std::size_t(n / 2) * 6;
        EXPECT_EQ(m.gpuBytes(n, comp), comp == LightFieldCompression::BC1
                                           ? texels / 2
                                           : 4 * (texels + texels / 4 + texels / 16));
    }
}

TEST(LightFieldGlossy, UniformLightFieldReadsBackExactly) {
    // A white furnace for the filter: every sample one colour, so every mip level holds it
    // and any weighted mean of lookups returns it, at any roughness, ray count, position and
    // view (grazing ones too); times E(n.v) for what the reflector shows. Tolerance: float
    // rounding of the weighted sums (1e-5).
    LightFieldAsset a = emptyAsset(5, 16, 1.2f);
    for (auto& s : a.slabs)
        for (std::size_t i = 0; i < s.data.size(); ++i)
            s.data[i] = std::uint8_t(i % 3 == 0 ? 200 : (i % 3 == 1 ? 120 : 40));
    const glm::vec3 want(srgbToLinearValue(200.f / 255.f), srgbToLinearValue(120.f / 255.f),
                         srgbToLinearValue(40.f / 255.f));
    const CpuLightFieldProbe lf(a);
    EXPECT_EQ(lf.maxLevel(), 4);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    float worst = 0.f, worstShown = 0.f;
    for (int i = 0; i < 4000; ++i) {
        const Config c = randomConfig(rng, a.halfCell(), i % 4 == 0 ? 0.f : 0.05f);
        const float r = i % 10 == 0 ? 1.f : 0.02f + 0.98f * u(rng);
        for (const int rays : {1, 2, 8, 16}) {
            const glm::vec3 got = lf.glossyRadiance(c.p, c.lhat, c.n, r, {rays, 0.f, true, false});
            worst = std::max(worst, float(maxAbs(glm::dvec3(got - want))));
        }
        const float e = ggxAlbedo(std::max(std::abs(glm::dot(c.n, c.lhat)), 1e-4f), r);
        const glm::vec3 shown = lf.reflectedRadiance(c.p, c.lhat, c.n, r);
        worstShown = std::max(worstShown, float(maxAbs(glm::dvec3(shown - e * want))));
    }
    std::printf("uniform light field: worst %.2e (filter), %.2e (times E)\n", worst, worstShown);
    EXPECT_LT(worst, 1e-5f);
    EXPECT_LT(worstShown, 1e-5f);
}
