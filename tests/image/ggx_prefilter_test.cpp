// The GGX prefiltered radiance chain against independent references: a white furnace and a
// brute-force quadrature of the GGX lobe over the sphere on a closed-form environment; also
// prints the prefilter's timing. Seams, level 0 and the distance footprints:
// ggx_prefilter_chain_test.cpp.
#include "engine/image/ggx_prefilter.h"
#include "ggx_prefilter_fixture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

namespace specula {
namespace {

using test::ggx_prefilter::Environment;
using test::ggx_prefilter::kPi;
using test::ggx_prefilter::makeCube;
using test::ggx_prefilter::texelCentre;

// A sky gradient, a soft highlight and a bright coloured disc with a hard edge.
const glm::dvec3 kHighlight = glm::normalize(glm::dvec3(0.3, 0.5, -0.8));
const glm::dvec3 kDisc = glm::normalize(glm::dvec3(-0.6, 0.2, 0.4));
constexpr double kDiscCos = 0.9928086358538663; // cos(0.12 rad)

glm::dvec3 testEnvironment(const glm::dvec3& d) {
    const double base = 0.6 + 0.4 * d.y;
    const double lobe = 3.0 * std::pow(std::max(0.0, glm::dot(d, kHighlight)), 16.0);
    glm::dvec3 c(base + lobe, base * 0.8 + lobe, base * 0.6 + 0.5 * lobe);
    if (glm::dot(d, kDisc) > kDiscCos) c += glm::dvec3(8.0, 4.0, 2.0);
    return c;
}

// GGX normal distribution, alpha = roughness^2.
double ggxD(double cosH, double alpha) {
    const double a2 = alpha * alpha;
    const double t = (a2 - 1.0) * cosH * cosH + 1.0;
    return a2 / (kPi * t * t);
}

// Brute-force  int L(l) D(h) (n.l) dl / int D(h) (n.l) dl  over n.l > 0 with n = v = r, by
// the midpoint rule on a polar grid about r: theta = (pi / 2) s^2 with s uniform (dense near
// the lobe's peak, dtheta = pi s ds), phi uniform. With v = n, h bisects n and l, so the
// angle of h is theta / 2.
glm::dvec3 bruteForceGgx(const Environment& env, glm::dvec3 r, double alpha, int nTheta, int nPhi) {
    r = glm::normalize(r);
    const glm::dvec3 up = std::fabs(r.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
    const glm::dvec3 t = glm::normalize(glm::cross(up, r)), b = glm::cross(r, t);
    std::vector<double> cosPhi(nPhi), sinPhi(nPhi);
    for (int j = 0; j < nPhi; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / nPhi;
        cosPhi[j] = std::cos(phi);
        sinPhi[j] = std::sin(phi);
    }
    glm::dvec3 num(0.0);
    double den = 0.0;
    for (int i = 0; i < nTheta; ++i) {
        const double s = (i + 0.5) / nTheta;
        const double theta = 0.5 * kPi * s * s, dTheta = kPi * s / nTheta;
        const double w = ggxD(std::cos(0.5 * theta), alpha) * std::cos(theta) * std::sin(theta) *
                         dTheta * (2.0 * kPi / nPhi);
        glm::dvec3 ring(0.0);
        for (int j = 0; j < nPhi; ++j) {
            const glm::dvec3 l =
                std::sin(theta) * (cosPhi[j] * t + sinPhi[j] * b) + std::cos(theta) * r;
            ring += env(l);
        }
        num += w * ring;
        den += w * nPhi;
    }
    return num / den;
}

double relativeError(glm::dvec3 got, glm::dvec3 want) {
    double e = 0.0;
    for (int c = 0; c < 3; ++c)
        e = std::max(e, std::fabs(got[c] - want[c]) / std::fabs(want[c]));
    return e;
}

// 1. A uniform white environment stays white at every level and every texel.
TEST(GgxPrefilter, WhiteFurnace) {
    const CubeFaces white = makeCube(64, [](const glm::dvec3&) { return glm::dvec3(1.0); });
    for (int samples : {1, 64, 256}) {
        GgxPrefilterOptions o;
        o.samples = samples;
        const CubeChain chain = prefilterGgx(white, o);
        double worst = 0.0;
        for (const CubeFaces& level : chain.levels)
            for (const Image& face : level)
                for (int y = 0; y < face.height; ++y)
                    for (int x = 0; x < face.width; ++x)
                        for (int c = 0; c < 3; ++c)
                            worst = std::max(worst, std::fabs(double(face.at(x, y)[c]) - 1.0));
        std::mt19937 rng(3);
        std::normal_distribution<float> g;
        std::uniform_real_distribution<float> lv(0.f, 5.f);
        for (int i = 0; i < 1000; ++i) {
            const glm::vec3 c = sampleChain(chain, glm::vec3(g(rng), g(rng), g(rng)), lv(rng));
            for (int k = 0; k < 3; ++k)
                worst = std::max(worst, std::fabs(double(c[k]) - 1.0));
        }
        std::printf("white furnace, %d samples: max |L - 1| = %.3g\n", samples, worst);
        EXPECT_LT(worst, 1e-5) << samples << " samples";
    }
}

// 2. Each glossy level against a brute-force quadrature of the GGX lobe on the analytic
// environment (not the cube: the reference knows nothing of texels, mips or samples). Two
// figures per level: texels at their centres (the filter's error alone), and sampleChain at
// arbitrary directions (the filter plus bilinear interpolation between texels).
TEST(GgxPrefilter, MatchesBruteForceIntegration) {
    const int n = 128, quad = 512;
    const CubeFaces cube = makeCube(n, testEnvironment);
    const CubeChain chain = prefilterGgx(cube);

    // The reference's own convergence, at its hardest: the narrowest lobe on the disc's rim.
    const glm::dvec3 rim = glm::normalize(kDisc + glm::dvec3(0.0, 0.1, 0.0));
    {
        const glm::dvec3 a = bruteForceGgx(testEnvironment, rim, 0.04, quad, quad);
        const glm::dvec3 b = bruteForceGgx(testEnvironment, rim, 0.04, 4 * quad, 4 * quad);
        std::printf("reference self-check (alpha 0.04, disc rim, %d^2 vs %d^2 points): "
                    "rel. diff %.2g\n",
                    quad, 4 * quad, relativeError(a, b));
        EXPECT_LT(relativeError(a, b), 2e-3);
    }

    // Directions: the disc's centre and rim, the highlight, a cube edge and corner, straight
    // down (where the sky is darkest), then random ones.
    std::vector<glm::dvec3> dirs = {kDisc,
                                    rim,
                                    glm::normalize(kDisc + glm::dvec3(0.15, 0.0, 0.0)),
                                    kHighlight,
                                    glm::dvec3(1, 1, 0),
                                    glm::dvec3(-1, 1, 1),
                                    glm::dvec3(0, -1, 0.001)};
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    while (dirs.size() < 32)
        dirs.push_back(glm::normalize(glm::dvec3(g(rng), g(rng), g(rng))));

    // Measured with the default options (64 samples at level 1 doubling per level, lod bias
    // 0.5) at N = 128, as max / mean relative error (per RGB channel) over 32 texels and over
    // 32 directions:
    //   level (r)   texels          directions
    //   1 (0.2)     0.025 / 0.010   0.038 / 0.015
    //   2 (0.4)     0.022 / 0.008   0.027 / 0.011
    //   3 (0.6)     0.020 / 0.007   0.022 / 0.008
    //   4 (0.8)     0.013 / 0.005   0.026 / 0.008
    //   5 (1.0)     0.011 / 0.004   0.067 / 0.017
    // The texel error is the filter's (finite samples, the blur of filtered importance
    // sampling); the 6.7% at level 5 is bilinear interpolation on its 4x4 faces, straight
    // down, where the lobe-averaged sky has its minimum (0.2) between four texel centres.
    // Bounds: about 1.5x the measurement.
    const double texelMax[] = {0, 0.04, 0.035, 0.03, 0.02, 0.017};
    const double texelMean[] = {0, 0.015, 0.012, 0.011, 0.008, 0.0065};
    const double dirMax[] = {0, 0.057, 0.04, 0.033, 0.04, 0.1};
    const double dirMean[] = {0, 0.022, 0.016, 0.012, 0.012, 0.025};
    for (int level = 1; level < int(chain.levels.size()); ++level) {
        const double alpha = double(chain.roughness[level]) * chain.roughness[level];
        const int m = chain.levels[level][0].width;
        std::vector<glm::ivec3> texels = {{0, 0, 0}, {3, m - 1, 0}, {4, m / 2, m / 2}};
        std::uniform_int_distribution<int> face(0, 5), xy(0, m - 1);
        while (texels.size() < 32)
            texels.push_back({face(rng), xy(rng), xy(rng)});

        std::vector<double> texelErr(texels.size()), dirErr(dirs.size());
        tbb::parallel_for(std::size_t(0), texels.size() + dirs.size(), [&](std::size_t i) {
            if (i < texels.size()) {
                const glm::ivec3 t = texels[i];
                const float* p = chain.levels[level][t.x].at(t.y, t.z);
                const glm::dvec3 want = bruteForceGgx(
                    testEnvironment, texelCentre(t.x, m, t.y, t.z), alpha, quad, quad);
                texelErr[i] = relativeError(glm::dvec3(p[0], p[1], p[2]), want);
            } else {
                const glm::dvec3 d = dirs[i - texels.size()];
                const glm::dvec3 want = bruteForceGgx(testEnvironment, d, alpha, quad, quad);
                const glm::dvec3 got(sampleChain(chain, glm::vec3(d), float(level)));
                dirErr[i - texels.size()] = relativeError(got, want);
            }
        });
        const auto maxOf = [](const std::vector<double>& v) {
            return *std::max_element(v.begin(), v.end());
        };
        const auto meanOf = [](const std::vector<double>& v) {
            double sum = 0.0;
            for (double e : v)
                sum += e;
            return sum / double(v.size());
        };
        std::printf("level %d (r = %.1f, %dx%d, %d samples): rel. error max / mean: texels "
                    "%.4f / %.4f, directions %.4f / %.4f\n",
                    level, chain.roughness[level], m, m, ggxChainSamples(level, {}),
                    maxOf(texelErr), meanOf(texelErr), maxOf(dirErr), meanOf(dirErr));
        EXPECT_LT(maxOf(texelErr), texelMax[level]) << "level " << level;
        EXPECT_LT(meanOf(texelErr), texelMean[level]) << "level " << level;
        EXPECT_LT(maxOf(dirErr), dirMax[level]) << "level " << level;
        EXPECT_LT(meanOf(dirErr), dirMean[level]) << "level " << level;
    }
}

TEST(GgxPrefilter, PrintsTiming) {
    for (int n : {128, 256}) {
        const CubeFaces cube = makeCube(n, testEnvironment);
        const auto start = std::chrono::steady_clock::now();
        const CubeChain chain = prefilterGgx(cube);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        std::printf("prefilterGgx %dx%d cube, 6 levels, 64 samples: %.0f ms\n", n, n, ms);
        EXPECT_EQ(chain.levels.size(), 6u);
    }
}

} // namespace
} // namespace specula
