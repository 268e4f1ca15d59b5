// The light-field probe's glossy lookup (issue 14; shaders/lightfield_glossy.glsl.h) on its
// CPU twin against brute-force GGX integrals on synthetic light fields known in closed form:
// a distant sky and walls at the focal depth. The filter's exact properties:
// lightfield_glossy_filter_test.cpp; the room's GGX truth and the shader:
// lightfield_glossy_test.cpp.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "lightfield_glossy_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/glm.hpp>

using namespace specula;
using test::lf_glossy::Config;
using test::lf_glossy::emptyAsset;
using test::lf_glossy::maxAbs;
using test::lf_glossy::randomConfig;
using test::lf_glossy::srgbCode;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Every sample of every slab from radiance(camera position, direction), the camera positions
// and pixel directions from the layout in lightfield_asset.h.
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
                cam[b] = h * (-3.f + 6.f * float(i) / float(a.cameras - 1));
                cam[c] = h * (-3.f + 6.f * float(j) / float(a.cameras - 1));
                for (int y = 0; y < a.res; ++y)
                    for (int x = 0; x < a.res; ++x) {
                        glm::vec3 d(0.f);
                        d[ax] = sign;
                        d[b] = -1.f + 2.f * (float(x) + 0.5f) / float(a.res);
                        d[c] = -1.f + 2.f * (float(y) + 0.5f) / float(a.res);
                        const glm::vec3 L = radiance(cam, glm::normalize(d));
                        const std::size_t at = (std::size_t(j * a.res + y) * std::size_t(n) +
                                                std::size_t(i * a.res + x)) *
                                               3;
                        for (int k = 0; k < 3; ++k)
                            data[at + std::size_t(k)] = srgbCode(L[k]);
                    }
            }
    }
}

// The GGX filter by brute force, independent of the lookup's visible-normal pattern: half
// vectors h ~ D(h) (n.h) on a 96 x 96 grid (tan^2 theta = alpha^2 u / (1 - u)), each
// l = reflect(-v, h) weighted by f (n.l) / pdf(l) = G2(v, l) (v.h) / ((n.v) (n.h)) (Smith
// height-correlated), normalised by the weights: what the lookup approximates.
template <typename F> glm::dvec3 ggxFilter(const Config& c, float roughness, F radiance) {
    const double alpha = double(roughness) * roughness, a2 = alpha * alpha;
    const glm::dvec3 n(c.n), wo = -glm::dvec3(c.v);
    const glm::dvec3 t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0))
                                                            : glm::cross(n, glm::dvec3(0, 1, 0)));
    const glm::dvec3 b = glm::cross(n, t);
    const double nv = glm::dot(n, wo);
    auto lambda = [&](double cs) {
        return 0.5 * (std::sqrt(1.0 + a2 * (1.0 - cs * cs) / (cs * cs)) - 1.0);
    };
    constexpr int kGrid = 96;
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            const double u1 = (i + 0.5) / kGrid, phi = 2.0 * kPi * (j + 0.5) / kGrid;
            const double cosH = 1.0 / std::sqrt(1.0 + a2 * u1 / (1.0 - u1));
            const double sinH = std::sqrt(std::max(0.0, 1.0 - cosH * cosH));
            const glm::dvec3 hv = sinH * std::cos(phi) * t + sinH * std::sin(phi) * b + cosH * n;
            const double vh = glm::dot(wo, hv);
            const glm::dvec3 l = 2.0 * vh * hv - wo;
            const double nl = glm::dot(n, l);
            if (vh <= 0.0 || nl <= 0.0) continue;
            const double w = vh / (nv * cosH * (1.0 + lambda(nv) + lambda(nl)));
            sum += w * glm::dvec3(radiance(glm::vec3(glm::normalize(l))));
            weights += w;
        }
    return sum / weights;
}

// A sky (colour a function of direction only) with detail at the scale of a glossy lobe:
// waves about 0.6 rad long.
glm::vec3 wavySky(glm::vec3 d) {
    return glm::vec3(0.45f + 0.3f * std::sin(5.f * d.x + 1.f) * std::cos(4.f * d.y),
                     0.45f + 0.3f * std::cos(6.f * d.z - 0.5f) * std::sin(3.f * d.x + 2.f),
                     0.4f + 0.25f * std::sin(4.f * d.y + 5.f * d.z));
}

// Six walls at axial depth `depth` beyond each slab's camera plane, with a pattern of about
// 0.5 m waves (as in lightfield_lookup_test.cpp, here a little coarser).
glm::vec3 traceWalls(glm::vec3 o, glm::vec3 d, float h, float depth) {
    const glm::vec3 a = glm::abs(d);
    const int ax = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    const float sign = d[ax] >= 0.f ? 1.f : -1.f;
    const glm::vec3 hit = o + (sign * (h + depth) - o[ax]) / d[ax] * d;
    const int b = (ax + 1) % 3, c = (ax + 2) % 3;
    const float w = 12.566371f;
    return glm::vec3(0.5f + 0.3f * std::sin(w * hit[b]), 0.5f + 0.3f * std::cos(w * hit[c]),
                     0.3f + 0.05f * float(ax));
}

// The lookups the analytic tests compare: the shader's (first), then the alternatives.
struct Lookup {
    const char* name;
    LightFieldGlossyOptions options;
};
const std::array<Lookup, 4> kLookups{
    {{"shader (footprint K)", {}},
     {"K8", {8, kLightFieldGlossyLevelBias, true, false}},
     {"mips only (K1)", {1, kLightFieldGlossyLevelBias, true, false}},
     {"K32 no mips", {32, 0.f, false, false}}}};

struct FilterErrors {
    std::array<double, kLookups.size()> mean{};
    double worst = 0.0;  // of the shader's lookup
    double mirror = 0.0; // mean of the mirror lookup
};

// Mean absolute error (largest channel) of each lookup of kLookups and of the mirror lookup
// against the brute-force filter, over n random configurations with n.v >= 0.2 and the mirror
// ray off the slabs' edges (its slopes within 0.75).
template <typename F>
FilterErrors filterErrors(const CpuLightFieldProbe& lf, float h, float r, int n, F radiance) {
    std::mt19937 rng(unsigned(100 * r) + 1);
    FilterErrors e;
    int done = 0;
    while (done < n) {
        const Config c = randomConfig(rng, h, 0.2f);
        const glm::vec3 a = glm::abs(c.lhat);
        const float big = std::max({a.x, a.y, a.z});
        if ((a.x != big && a.x > 0.75f * big) || (a.y != big && a.y > 0.75f * big) ||
            (a.z != big && a.z > 0.75f * big))
            continue;
        const glm::dvec3 want = ggxFilter(c, r, [&](glm::vec3 l) { return radiance(c.p, l); });
        for (std::size_t k = 0; k < kLookups.size(); ++k) {
            const double err = maxAbs(
                glm::dvec3(lf.glossyRadiance(c.p, c.lhat, c.n, r, kLookups[k].options)) - want);
            e.mean[k] += err / n;
            if (k == 0) e.worst = std::max(e.worst, err);
        }
        e.mirror += maxAbs(glm::dvec3(lf.radiance(c.p, c.lhat)) - want) / n;
        ++done;
    }
    return e;
}

void printErrors(const char* what, float r, const FilterErrors& e) {
    std::printf("%s, r %.2f: mean error", what, r);
    for (std::size_t k = 0; k < kLookups.size(); ++k) {
        std::printf(" %s %.4f", kLookups[k].name, e.mean[k]);
        if (k == 0) std::printf(" (worst %.4f)", e.worst);
        std::printf(",");
    }
    std::printf(" mirror %.4f\n", e.mirror);
}

} // namespace

TEST(LightFieldGlossy, DistantSkyMatchesTheGgxFilter) {
    // Every camera sees the same sky; with disparity 0 the lookup is a filtered environment
    // map, so this holds the lobe's shape (rays, weights, mip levels from Omega) to the GGX
    // filter computed by brute force. Measured (NUM 4, RES 64, 300 configurations), mean
    // error at r = 0.2 / 0.35 / 0.5: shader (footprint K) 0.0071 / 0.0098 / 0.0098; K 8 0.0075 /
    // 0.024 / 0.024; the mips alone (K 1) 0.021 / 0.057 / 0.058; 32 rays without mips 0.0071 /
    // 0.010 / 0.010; the mirror lookup 0.025 / 0.089 / 0.148. Bounds: under half the mirror
    // lookup's error and under 0.015 (1.5x the worst measured).
    LightFieldAsset a = emptyAsset(4, 64, 1.f);
    fill(a, [](glm::vec3, glm::vec3 d) { return wavySky(d); });
    const CpuLightFieldProbe lf(a, 0.f);
    for (const float r : {0.2f, 0.35f, 0.5f}) {
        const FilterErrors e = filterErrors(lf, a.halfCell(), r, 300,
                                            [](glm::vec3, glm::vec3 l) { return wavySky(l); });
        printErrors("sky", r, e);
        EXPECT_LT(e.mean[0], e.mirror / 2.0) << r;
        EXPECT_LT(e.mean[0], 0.015) << r;
    }
}

TEST(LightFieldGlossy, WallAtTheFocalDepthMatchesTheGgxFilter) {
    // Walls at the focal depth with a pattern: the rays' parallax and the mips' magnification
    // F = 1 + along / z_f (a camera nearer the wall than the reflector sees the lobe's spot
    // wider) are both exercised. Reference: the brute-force filter over rays traced from p to
    // the walls. Measured (NUM 8, RES 64), mean error at r = 0.2 / 0.35 / 0.5: shader (footprint
    // K) 0.013 / 0.018 / 0.013 (K 16 everywhere: 0.011 / 0.018 / 0.013); K 8 0.024 / 0.023 / 0.014;
    // the mips alone 0.083 / 0.045 / 0.021; 32 rays without mips 0.016 / 0.028 / 0.040 (level 0
    // aliases the wall's pattern, which the mips average); the mirror lookup 0.17 / 0.22 / 0.24.
    // Bounds: under a fifth of the mirror lookup's error and under 0.025 (1.4x the worst measured).
    LightFieldAsset a = emptyAsset(8, 64, 1.f);
    const float h = a.halfCell(), z0 = 1.5f;
    fill(a, [&](glm::vec3 o, glm::vec3 d) { return traceWalls(o, d, h, z0); });
    const CpuLightFieldProbe lf(a, disparityForDepth(a, z0));
    for (const float r : {0.2f, 0.35f, 0.5f}) {
        const FilterErrors e = filterErrors(
            lf, h, r, 300, [&](glm::vec3 p, glm::vec3 l) { return traceWalls(p, l, h, z0); });
        printErrors("walls", r, e);
        EXPECT_LT(e.mean[0], e.mirror / 5.0) << r;
        EXPECT_LT(e.mean[0], 0.025) << r;
    }
}
