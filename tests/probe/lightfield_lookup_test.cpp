// The light-field-slab lookup (CPU twin of the shader) on its own: slab coverage for hard
// rays, and exactness against synthetic light fields whose every sample is known in closed
// form. No GL, no Embree.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/image_io/image_io.h"
#include "engine/math/cube_face.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace specula;

namespace {

LightFieldAsset emptyAsset(int num, int res, float cell) {
    LightFieldAsset a;
    a.cellSize = cell;
    a.cameras = num;
    a.res = res;
    for (auto& s : a.slabs)
        s.data.assign(a.layerBytes(), 0);
    return a;
}

// Fills every sample of every slab from `radiance(origin, dir)`, computing each camera's
// position and each pixel's direction from the layout described in lightfield_asset.h,
// written out here independently of the lookup code.
template <typename F> void fill(LightFieldAsset& a, F radiance) {
    const int n = a.atlasSize();
    const float h = a.halfCell();
    for (int slab = 0; slab < 6; ++slab) {
        const int ax = slab / 2, b = (ax + 1) % 3, c = (ax + 2) % 3;
        const float sign = slab % 2 ? -1.f : 1.f;
        std::vector<std::uint8_t>& data = a.slabs[std::size_t(slab)].data;
        for (int j = 0; j < a.cameras; ++j)
            for (int i = 0; i < a.cameras; ++i) {
                glm::vec3 cam(0.f);
                cam[ax] = sign * h;
                cam[b] = -3.f * h + 6.f * h * float(i) / float(a.cameras - 1);
                cam[c] = -3.f * h + 6.f * h * float(j) / float(a.cameras - 1);
                for (int y = 0; y < a.res; ++y)
                    for (int x = 0; x < a.res; ++x) {
                        glm::vec3 d(0.f);
                        d[ax] = sign;
                        d[b] = -1.f + 2.f * (float(x) + 0.5f) / float(a.res);
                        d[c] = -1.f + 2.f * (float(y) + 0.5f) / float(a.res);
                        const glm::vec3 L = radiance(cam, d);
                        std::uint8_t* p =
                            &data[(std::size_t(j * a.res + y) * n + std::size_t(i * a.res + x)) *
                                  3];
                        for (int k = 0; k < 3; ++k)
                            p[k] = std::uint8_t(
                                std::lround(255.f * linearToSrgbValue(std::clamp(L[k], 0.f, 1.f))));
                    }
            }
    }
}

// The colour of a point on a wall: waves with a 1 m period, smooth enough for bilinear
// interpolation between pixels (a few cm apart) and far from linear across cameras (0.43 m
// apart), so only the right disparity reads it back.
glm::vec3 wallColour(glm::vec3 hit, int ax) {
    const int b = (ax + 1) % 3, c = (ax + 2) % 3;
    const float w = 6.2831853f;
    return glm::vec3(0.5f + 0.3f * std::sin(w * hit[b]), 0.5f + 0.3f * std::cos(w * hit[c]),
                     0.3f + 0.05f * float(ax));
}

// Six walls: the plane at axial distance `depth` beyond each slab's camera plane.
glm::vec3 traceWalls(glm::vec3 o, glm::vec3 d, float h, float depth) {
    const glm::vec3 a = glm::abs(d);
    const int ax = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    const float sign = d[ax] >= 0.f ? 1.f : -1.f;
    const float t = (sign * (h + depth) - o[ax]) / d[ax];
    return wallColour(o + t * d, ax);
}

} // namespace

TEST(LightFieldLookup, SlabIndicesStayInRangeForMillionsOfHardRays) {
    // Continuous camera indices must lie in [0, NUM-1] and pixel indices in
    // [-0.5, RES-0.5] for every ray from a point in the cell, whatever the direction: random,
    // on ties between components (face edges and corners), parallel to the camera planes of
    // the other slabs (components exactly 0), tiny, and from points on the cell's faces,
    // edges and corners. The slab must be the cube face of the same direction (tie rule X
    // over Y over Z). Tolerance: 1e-4 of an index (float rounding of the plane intersection).
    const LightFieldAsset a = emptyAsset(8, 64, 1.5f);
    const CpuLightFieldProbe lf(a);
    const float h = a.halfCell();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    std::uniform_int_distribution<int> pick(0, 9);
    const float hi = float(a.cameras - 1), pixHi = float(a.res) - 0.5f;
    long checked = 0, bad = 0;
    auto check = [&](glm::vec3 p, glm::vec3 d) {
        const LightFieldCoords c = lf.coords(p, d);
        ++checked;
        const bool finite = std::isfinite(c.camera.x) && std::isfinite(c.camera.y) &&
                            std::isfinite(c.pixel.x) && std::isfinite(c.pixel.y);
        const bool inRange = c.camera.x >= -1e-4f && c.camera.x <= hi + 1e-4f &&
                             c.camera.y >= -1e-4f && c.camera.y <= hi + 1e-4f &&
                             c.pixel.x >= -0.5f - 1e-4f && c.pixel.x <= pixHi + 1e-4f &&
                             c.pixel.y >= -0.5f - 1e-4f && c.pixel.y <= pixHi + 1e-4f;
        const int face = int(glsl::cubeFaceUv(d).z);
        const bool sameFace = !(glm::dot(d, d) > 0.f) || c.slab == face;
        const glm::vec3 col = lf.radiance(p, d);
        const bool finiteColour = std::isfinite(col.x + col.y + col.z);
        if (!(finite && inRange && sameFace && finiteColour)) {
            if (++bad < 5)
                ADD_FAILURE() << "p " << p.x << "," << p.y << "," << p.z << " d " << d.x << ","
                              << d.y << "," << d.z << " -> slab " << c.slab << " (face " << face
                              << ") camera " << c.camera.x << "," << c.camera.y << " pixel "
                              << c.pixel.x << "," << c.pixel.y;
        }
    };
    for (int i = 0; i < 2'000'000; ++i) {
        glm::vec3 p(h * u(rng), h * u(rng), h * u(rng));
        // A third of the points on the cell's faces, edges or corners.
        for (int k = 0; k < 3; ++k)
            if (pick(rng) < 3) p[k] = (u(rng) < 0.f ? -h : h);
        glm::vec3 d(u(rng), u(rng), u(rng));
        switch (pick(rng)) {
        case 0:
            d.y = d.x;
            break; // tie X = Y (edge)
        case 1:
            d.z = -d.y;
            break; // tie |Y| = |Z|
        case 2:
            d = glm::vec3(d.x, (u(rng) < 0 ? -1.f : 1.f) * std::abs(d.x), -d.x);
            break; // corner
        case 3:
            d[pick(rng) % 3] = 0.f;
            break; // parallel to a plane
        case 4:
            d[pick(rng) % 3] = 0.f, d[pick(rng) % 3] = 0.f;
            break; // along an axis or 0
        case 5:
            d *= 1e-30f;
            break; // tiny
        default:
            break;
        }
        check(p, d);
    }
    // The special directions exactly, from the corners and the centre.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const glm::vec3 dirs[] = {{1, 1, 1},           {-1, 1, -1},    {1, -1, 0},  {0, 1, 1},
                              {0, 0, -1},          {0, 0, 0},      {nan, 0, 1}, {inf, 1, 0},
                              {1e-38f, 1e-38f, 0}, {-0.f, -0.f, 1}};
    for (int corner = 0; corner < 9; ++corner) {
        const glm::vec3 p =
            corner == 8 ? glm::vec3(0.f)
                        : glm::vec3(corner & 1 ? h : -h, corner & 2 ? h : -h, corner & 4 ? h : -h);
        for (const glm::vec3& d : dirs)
            check(p, d);
    }
    check(glm::vec3(nan, 0.f, 0.f), glm::vec3(0.f, 1.f, 0.f));
    std::printf("coverage: %ld rays, %ld out of range\n", checked, bad);
    EXPECT_EQ(bad, 0);
}

TEST(LightFieldLookup, DistantEnvironmentIsExactFromAnywhereWithZeroDisparity) {
    // An environment at infinity (colour a function of direction only): every camera holds
    // the same image, so with disparity 0 the lookup is the bilinear image of the direction,
    // from any point of the cell. Reference: the colour function at the direction itself;
    // tolerance: 8-bit sRGB quantisation plus bilinear error of a smooth function (0.01).
    LightFieldAsset a = emptyAsset(4, 32, 1.f);
    auto sky = [](glm::vec3 d) {
        d = glm::normalize(d);
        return glm::vec3(0.5f + 0.4f * d.x, 0.5f + 0.4f * d.y, 0.5f + 0.4f * d.z);
    };
    fill(a, [&](glm::vec3, glm::vec3 d) { return sky(d); });
    const CpuLightFieldProbe lf(a, 0.f);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    float worst = 0.f;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p = 0.5f * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d(u(rng), u(rng), u(rng));
        if (glm::length(d) < 1e-3f) continue;
        const glm::vec3 err = glm::abs(lf.radiance(p, d) - sky(d));
        worst = std::max({worst, err.x, err.y, err.z});
    }
    std::printf("distant environment: worst error %.4f\n", worst);
    EXPECT_LT(worst, 0.01f);
}

TEST(LightFieldLookup, FocalDisparityMakesAWallAtThatDepthExact) {
    // Each slab looks at a wall at axial depth z0 beyond its camera plane, with a wavy
    // pattern. With the disparity of that depth (Yu eq. 6), each of the four cameras is
    // sampled where it saw the true hit point, so the blend is exact up to quantisation and
    // bilinear error between pixels (0.02); with disparity 0 the four cameras disagree. This pins
    // the plane intersection, the camera/pixel mapping and the sign of the disparity shift. Rays
    // keep |slope| <= 0.5 so the shifted pixel never reaches a tile's clamped edge.
    LightFieldAsset a = emptyAsset(8, 64, 1.f);
    const float h = a.halfCell(), z0 = 1.5f;
    fill(a, [&](glm::vec3 o, glm::vec3 d) { return traceWalls(o, d, h, z0); });
    const CpuLightFieldProbe focused(a, disparityForDepth(a, z0));
    const CpuLightFieldProbe unfocused(a, 0.f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    double worstFocused = 0, sumFocused = 0, sumUnfocused = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const glm::vec3 p(h * u(rng), h * u(rng), h * u(rng));
        const int ax = i % 3;
        glm::vec3 d(0.5f * u(rng), 0.5f * u(rng), 0.5f * u(rng));
        d[ax] = u(rng) < 0.f ? -1.f : 1.f;
        const glm::vec3 want = traceWalls(p, d, h, z0);
        const double e = glm::length(focused.radiance(p, d) - want);
        worstFocused = std::max(worstFocused, e);
        sumFocused += e;
        sumUnfocused += glm::length(unfocused.radiance(p, d) - want);
    }
    std::printf("wall at the focal depth: worst %.4f, mean %.5f; disparity 0: mean %.5f\n",
                worstFocused, sumFocused / n, sumUnfocused / n);
    EXPECT_LT(worstFocused, 0.02);
    EXPECT_GT(sumUnfocused, 5.0 * sumFocused);
}

TEST(LightFieldLookup, StorageFitsTheGlLimitsAndBadSizesAreRefused) {
    LightFieldAsset paper = emptyAsset(2, 4, 1.f);
    paper.cameras = 32, paper.res = 128;
    EXPECT_EQ(paper.atlasSize(), 4096);
    EXPECT_EQ(paper.diskBytes(), std::size_t(6) * 4096 * 4096 * 3);
    EXPECT_EQ(paper.gpuBytes(), std::size_t(6) * 4096 * 4096 * 4);
    paper.compression = LightFieldCompression::BC1;
    EXPECT_LE(paper.gpuBytes(), std::size_t(64) << 20);
    EXPECT_NO_THROW(validateLightFieldSize(32, 128, 1.5f, LightFieldCompression::BC1, ""));
    EXPECT_THROW(validateLightFieldSize(64, 512, 1.5f, LightFieldCompression::None, ""), Error);
    EXPECT_THROW(validateLightFieldSize(8, 62, 1.5f, LightFieldCompression::BC1, ""), Error);
    EXPECT_THROW(validateLightFieldSize(1, 64, 1.5f, LightFieldCompression::None, ""), Error);
    try {
        validateLightFieldSize(8, 64, 0.f, LightFieldCompression::None, "m.json");
        ADD_FAILURE() << "a zero cell was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "m.json");
        EXPECT_EQ(e.field(), "cell.size");
    }
}
