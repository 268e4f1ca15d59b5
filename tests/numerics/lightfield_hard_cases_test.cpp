// docs/design.md §7 hard cases for the light-field-slab flavour, on its C++ twin: reflected rays
// parallel to a slab's camera plane, exact ties of the largest component (slab edges and
// corners), reflectors on the very boundary of the cell, zero/NaN/inf directions. The light
// field holds a distant environment (colour a function of direction only), for which the
// lookup with disparity 0 is exact from anywhere in the cell up to 8-bit sRGB quantisation
// and bilinear filtering: the reference is the colour function at the ray's direction.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/image_io/image_io.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

using namespace specula;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

glm::vec3 sky(glm::vec3 d) {
    d = glm::normalize(d);
    return glm::vec3(0.5f + 0.4f * d.x, 0.5f + 0.4f * d.y, 0.5f + 0.4f * d.z);
}

// Every camera of every slab sees the same image of the sky (layout of lightfield_asset.h).
LightFieldAsset skyLightField(int cameras, int res, float cell) {
    LightFieldAsset a;
    a.cellSize = cell;
    a.cameras = cameras;
    a.res = res;
    const int n = a.atlasSize();
    for (int slab = 0; slab < 6; ++slab) {
        const int ax = slab / 2, b = (ax + 1) % 3, c = (ax + 2) % 3;
        std::vector<std::uint8_t>& data = a.slabs[std::size_t(slab)].data;
        data.assign(a.layerBytes(), 0);
        for (int j = 0; j < cameras; ++j)
            for (int i = 0; i < cameras; ++i)
                for (int y = 0; y < res; ++y)
                    for (int x = 0; x < res; ++x) {
                        glm::vec3 d(0.f);
                        d[ax] = slab % 2 ? -1.f : 1.f;
                        d[b] = -1.f + 2.f * (float(x) + 0.5f) / float(res);
                        d[c] = -1.f + 2.f * (float(y) + 0.5f) / float(res);
                        const glm::vec3 L = sky(d);
                        std::uint8_t* p = &data[(std::size_t(j * res + y) * std::size_t(n) +
                                                 std::size_t(i * res + x)) *
                                                3];
                        for (int k = 0; k < 3; ++k)
                            p[k] = std::uint8_t(std::lround(255.f * linearToSrgbValue(L[k])));
                    }
    }
    return a;
}

bool finite3(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

struct Tally {
    double worst = 0.0;
    long n = 0, nonFinite = 0;
    void add(glm::vec3 got, glm::vec3 want) {
        ++n;
        if (!finite3(got)) {
            ++nonFinite;
            return;
        }
        const glm::vec3 e = glm::abs(got - want);
        worst = std::max({worst, double(e.x), double(e.y), double(e.z)});
    }
    void report(const char* kase, double bound) const {
        std::printf("[numerics] %-34s lightfield cpu  rays %8ld  worst %.3e  bound %.1e%s\n", kase,
                    n, worst, bound, nonFinite ? "  NON-FINITE" : "");
        EXPECT_EQ(nonFinite, 0) << kase;
        EXPECT_LE(worst, bound) << kase;
    }
};

class LightFieldHardCases : public ::testing::Test {
protected:
    static void SetUpTestSuite() { asset_ = new LightFieldAsset(skyLightField(4, 32, 1.f)); }
    static void TearDownTestSuite() { delete asset_; }
    static LightFieldAsset* asset_;
};
LightFieldAsset* LightFieldHardCases::asset_ = nullptr;

// Per-channel bound: 8-bit sRGB step (~0.004 at 0.9) plus bilinear error of the smooth sky
// over one pixel (~0.005), the tolerance of the light-field lookup tests.
constexpr double kBound = 0.012;

} // namespace

TEST_F(LightFieldHardCases, RaysParallelToTheCameraPlane) {
    // D_axis -> 0 for the slab axis: such a ray belongs to another slab (largest component),
    // and the chosen slab's camera plane meets it; D_z down to 0 and denormal.
    const CpuLightFieldProbe lf(*asset_, 0.f);
    std::mt19937 rng(43);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    Tally t;
    for (float dz : {0.f, 1e-40f, -1e-40f, 1e-20f, 1e-7f, -1e-7f, 1e-3f})
        for (int i = 0; i < 500; ++i) {
            const glm::vec3 p(u(rng), u(rng), u(rng));
            const float phi = 6.2831853f * (u(rng) + 0.5f);
            const glm::vec3 d(std::cos(phi), std::sin(phi), dz);
            t.add(lf.radiance(p, d), sky(d));
        }
    t.report("lf: rays parallel to camera plane", kBound);
}

TEST_F(LightFieldHardCases, ExactTiesOfTheLargestComponent) {
    const CpuLightFieldProbe lf(*asset_, 0.f);
    std::mt19937 rng(47);
    std::uniform_real_distribution<float> u(-0.5f, 0.5f);
    Tally t;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k) {
                if (!(i || j || k)) continue;
                for (float s : {1.f, 1e-30f, 1e30f})
                    for (int r = 0; r < 50; ++r) {
                        const glm::vec3 d = s * glm::vec3(float(i), float(j), float(k));
                        const glm::vec3 p(u(rng), u(rng), u(rng));
                        t.add(lf.radiance(p, d), sky(glm::vec3(float(i), float(j), float(k))));
                        const LightFieldCoords c = lf.coords(p, d);
                        EXPECT_GE(c.slab, 0);
                        EXPECT_LT(c.slab, 6);
                    }
            }
    t.report("lf: ties (slab edges and corners)", kBound);
}

TEST_F(LightFieldHardCases, ReflectorOnTheCellBoundary) {
    const CpuLightFieldProbe lf(*asset_, 0.f);
    std::mt19937 rng(53);
    std::normal_distribution<float> g;
    const float h = 0.5f * asset_->cellSize;
    Tally t;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            for (int k = -1; k <= 1; ++k)
                for (int r = 0; r < 200; ++r) {
                    const glm::vec3 p = h * glm::vec3(float(i), float(j), float(k));
                    glm::vec3 d(g(rng), g(rng), g(rng));
                    if (glm::length(d) < 1e-3f) continue;
                    t.add(lf.radiance(p, d), sky(d));
                }
    t.report("lf: reflector on the cell boundary", kBound);
}

TEST_F(LightFieldHardCases, DegenerateDirectionsAndPositionsStayFinite) {
    const CpuLightFieldProbe lf(*asset_, 0.f);
    for (glm::vec3 d :
         {glm::vec3(0.f), glm::vec3(kNaN), glm::vec3(kInf, 0.f, 0.f), glm::vec3(kInf, -kInf, 1.f),
          glm::vec3(1e-45f, 0.f, 0.f), glm::vec3(FLT_MAX, FLT_MAX, FLT_MAX)})
        for (glm::vec3 p :
             {glm::vec3(0.f), glm::vec3(0.5f), glm::vec3(kNaN), glm::vec3(1e5f, -1e5f, 1e5f)}) {
            const glm::vec3 c = lf.radiance(p, d);
            EXPECT_TRUE(finite3(c)) << d.x << "," << d.y << "," << d.z << " at " << p.x;
            const LightFieldCoords co = lf.coords(p, d);
            EXPECT_GE(co.slab, 0);
            EXPECT_LT(co.slab, 6);
        }
}
