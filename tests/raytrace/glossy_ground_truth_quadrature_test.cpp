// The glossy (GGX) ground truth's energy: a white furnace returns the GGX directional albedo
// (F = 1, Smith height-correlated) and a graded sky the integral of the lobe, both computed
// here by quadrature from the definitions. The tracer's behaviour (roughness 0, noise, seeds,
// tint, bounces, environmentOnly): glossy_ground_truth_test.cpp.
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/transform_system.h"
#include "raytrace/test_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

namespace specula {
namespace {

using namespace testscenes;

// --- White furnace -------------------------------------------------------------------------
//
// Under a sky of radiance 1 everywhere, a rough reflector with F = 1 returns its directional
// albedo E(v) = integral over n.l > 0 of D(h) G2(v, l) / (4 n.v) dl. Computed here by
// midpoint quadrature in a frame with n = +Z, written from the definitions and not from the
// tracer's sampling: D is GGX, G2 = 1 / (1 + Lambda(v) + Lambda(l)).

double ggxD(double cosH, double alpha) {
    const double a2 = alpha * alpha;
    const double k = cosH * cosH * (a2 - 1.0) + 1.0;
    return a2 / (glm::pi<double>() * k * k);
}

double ggxLambda(double cosTheta, double alpha) {
    const double c2 = cosTheta * cosTheta;
    const double tan2 = (1.0 - c2) / c2;
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// Over half vectors h: dl = 4 (v.h) dh, and with xi = t / (1 + t), t = tan^2(theta_h) /
// alpha^2, D(h) cos(theta_h) dh = dxi dphi / (2 pi), so
//   E = integral over [0,1) x [0,2pi) of G2 (v.h) / ((n.v) (n.h)) [v.h > 0, n.l > 0]
//       dxi dphi / (2 pi).
// GGX has long tails (a share ~alpha^2 of the normals lies beyond 45 degrees, where l falls
// below the horizon), so xi = 1 - exp(-s) is integrated over s in [0, 40]: the tail gets
// as many nodes as the core. The integrand is bounded and goes to 0 continuously at the
// horizon (G2 -> 0).
// `sky(l)`: the radiance arriving from l (local frame); the albedo takes 1.
using LocalSky = std::function<double(const glm::dvec3&)>;

double reflectedOverHalfVectors(double alpha, double cosV, int nS, int nPhi, const LocalSky& sky) {
    const glm::dvec3 v(std::sqrt(1.0 - cosV * cosV), 0.0, cosV);
    const double lambdaV = ggxLambda(cosV, alpha);
    constexpr double kS = 40.0;
    double sum = 0.0;
    for (int i = 0; i < nS; ++i) {
        // Midpoint in s for the integrand, the exact mass exp(-s) ds of each cell.
        const double s = kS * (i + 0.5) / nS;
        const double oneMinusXi = std::exp(-s);
        const double mass = std::exp(-kS * i / nS) - std::exp(-kS * (i + 1) / nS);
        const double tanTheta = alpha * std::sqrt((1.0 - oneMinusXi) / oneMinusXi);
        const double cosH = 1.0 / std::sqrt(1.0 + tanTheta * tanTheta);
        const double sinH = tanTheta * cosH;
        double ring = 0.0;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = glm::two_pi<double>() * (j + 0.5) / nPhi;
            const glm::dvec3 h(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
            const double vh = glm::dot(v, h);
            if (vh <= 0.0) continue;
            const glm::dvec3 l = 2.0 * vh * h - v;
            if (l.z <= 0.0) continue;
            const double g2 = 1.0 / (1.0 + lambdaV + ggxLambda(l.z, alpha));
            ring += g2 * vh / (cosV * cosH) * (sky ? sky(l) : 1.0);
        }
        sum += ring * mass;
    }
    return sum / nPhi;
}

double albedoOverHalfVectors(double alpha, double cosV, int nS, int nPhi) {
    return reflectedOverHalfVectors(alpha, cosV, nS, nPhi, {});
}

// Directly over light directions, in polar coordinates about the mirror direction r with a
// polar angle graded towards r (beta = pi s^3): a second route, for the wider lobes.
double albedoOverLightDirections(double alpha, double cosV, int nS, int nPhi) {
    const glm::dvec3 v(std::sqrt(1.0 - cosV * cosV), 0.0, cosV);
    const glm::dvec3 r(-v.x, 0.0, v.z);
    const glm::dvec3 e1(r.z, 0.0, -r.x), e2(0.0, 1.0, 0.0);
    const double lambdaV = ggxLambda(cosV, alpha);
    double sum = 0.0;
    for (int i = 0; i < nS; ++i) {
        const double s = (i + 0.5) / nS;
        const double beta = glm::pi<double>() * s * s * s;
        const double dBeta = 3.0 * glm::pi<double>() * s * s / nS;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = glm::two_pi<double>() * (j + 0.5) / nPhi;
            const glm::dvec3 l =
                std::cos(beta) * r + std::sin(beta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
            if (l.z <= 0.0) continue;
            const glm::dvec3 h = glm::normalize(v + l);
            const double g2 = 1.0 / (1.0 + lambdaV + ggxLambda(l.z, alpha));
            const double f = ggxD(h.z, alpha) * g2 / (4.0 * cosV); // f (n.l), F = 1
            sum += f * std::sin(beta) * dBeta * (glm::two_pi<double>() / nPhi);
        }
    }
    return sum;
}

TEST(GlossyGroundTruth, AlbedoQuadraturesAgree) {
    // The two routes to the reference agree, and a near-mirror keeps all its energy.
    for (const double roughness : {0.35, 0.6, 1.0})
        for (const double cosV : {1.0, 0.5, 0.2}) {
            const double alpha = roughness * roughness;
            const double a = albedoOverHalfVectors(alpha, cosV, 2048, 1024);
            const double b = albedoOverLightDirections(alpha, cosV, 2048, 1024);
            EXPECT_NEAR(a, b, 2e-4) << "roughness " << roughness << " cos " << cosV;
            EXPECT_LE(a, 1.0);
        }
    EXPECT_NEAR(albedoOverHalfVectors(1e-6, 0.7, 512, 256), 1.0, 1e-5);
}

TEST(GlossyGroundTruth, WhiteFurnaceReturnsTheGgxAlbedo) {
    // A rough mirror plane y = 0 under a white sky, nothing else.
    const Image white = solidImage(8, 4, glm::vec3(1.f));
    ecs::Registry reg;
    const ecs::Entity plane =
        addMesh(reg, quad({-100.f, 0.f, 100.f}, {200.f, 0.f, 0.f}, {0.f, 0.f, -200.f}));
    updateWorldTransforms(reg);
    constexpr int kSamples = 256, kGrid = 16, kRays = kGrid * kGrid;
    std::printf("roughness  view   E(quadrature)  mean(estimator)  error      sd/sqrt(P)  "
                "bound\n");
    for (const float roughness : {0.1f, 0.35f, 0.6f, 1.f}) {
        TraceOptions opt;
        opt.mirrors = {plane};
        opt.sky = &white;
        opt.mirrorRoughness = [roughness](ecs::Entity, glm::vec2) { return roughness; };
        opt.glossySamples = kSamples;
        const GroundTruthTracer tracer(reg, opt);
        for (const double viewDeg : {0.0, 45.0, 70.0, 85.0}) {
            const double alpha = double(roughness) * roughness;
            const double cosV = std::cos(glm::radians(viewDeg));
            const double reference = albedoOverHalfVectors(alpha, cosV, 4096, 1024);
            // One estimate per ray, each ray its own randomisation (a different hit point).
            const glm::vec3 v(float(std::sin(glm::radians(viewDeg))), float(cosV), 0.f);
            double sum = 0.0, sum2 = 0.0;
            for (int i = 0; i < kRays; ++i) {
                const glm::vec3 p(-1.f + 2.f * float(i % kGrid) / kGrid, 0.f,
                                  -1.f + 2.f * float(i / kGrid) / kGrid);
                const glm::vec3 c = tracer.radiance(p + v, -v);
                ASSERT_EQ(c.r, c.g);
                ASSERT_EQ(c.r, c.b);
                ASSERT_GE(c.r, 0.f);
                ASSERT_LE(c.r, 1.f + 1e-6f);
                sum += c.r;
                sum2 += double(c.r) * c.r;
            }
            const double mean = sum / kRays;
            const double sd = std::sqrt(std::max(0.0, sum2 / kRays - mean * mean));
            // Each sample's weight G2 / G1 lies in [0, 1] with mean E, so its variance is at
            // most E (1 - E); Owen-scrambled (0, 2)-nets have at most twice the Monte Carlo
            // variance (Owen 1997), and the kRays estimates are independent: the mean's
            // standard deviation is at most sqrt(2 E (1 - E) / (N P)). Four of those, plus
            // 2e-5 for float sums and the quadrature.
            const double bound =
                4.0 * std::sqrt(2.0 * reference * (1.0 - reference) / (double(kSamples) * kRays)) +
                2e-5;
            std::printf("%9.2f  %4.0f   %13.6f  %15.6f  %+.2e  %.2e    %.2e\n", roughness, viewDeg,
                        reference, mean, mean - reference, sd / std::sqrt(kRays), bound);
            EXPECT_NEAR(mean, reference, bound)
                << "roughness " << roughness << " view " << viewDeg << " deg";
            EXPECT_LE(mean, 1.0 + 1e-6);
        }
    }
}

// The furnace checks the weights' integral; a sky that varies checks where the samples go:
// its gradient the lobe's lean away from the mirror direction, its curvature the lobe's
// width. L(d) = 1 + 0.5 d.x + 0.5 d.z^2 in the scene (the plane's normal is +Y, the view in
// the XY plane), tabulated finely enough that bilinear lookup adds < 1e-5.
TEST(GlossyGroundTruth, GradedSkyMatchesQuadratureOfTheLobe) {
    auto radianceOf = [](glm::dvec3 d) { return 1.0 + 0.5 * d.x + 0.5 * d.z * d.z; };
    Image sky(2048, 1024, 3);
    for (int j = 0; j < sky.height; ++j)
        for (int i = 0; i < sky.width; ++i) {
            // The inverse of equirectUv at the texel centre.
            const double theta = glm::pi<double>() * (j + 0.5) / sky.height;
            const double phi = glm::two_pi<double>() * ((i + 0.5) / sky.width - 0.5);
            const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                               -std::sin(theta) * std::cos(phi));
            const float value = float(radianceOf(d));
            sky.at(i, j)[0] = sky.at(i, j)[1] = sky.at(i, j)[2] = value;
        }
    ecs::Registry reg;
    const ecs::Entity plane =
        addMesh(reg, quad({-100.f, 0.f, 100.f}, {200.f, 0.f, 0.f}, {0.f, 0.f, -200.f}));
    updateWorldTransforms(reg);
    {
        TraceOptions skyOnly;
        skyOnly.sky = &sky;
        const GroundTruthTracer bare(reg, skyOnly);
        for (const glm::vec3 d : {glm::vec3(0.3f, 0.8f, -0.5f), glm::vec3(-0.9f, 0.1f, 0.4f)})
            ASSERT_NEAR(bare.sky(d).r, radianceOf(glm::normalize(glm::dvec3(d))), 1e-5);
    }
    // Local frame of the quadrature (n = +Z, v in XZ) to the scene's: (x, y, z) -> (x, z, y).
    const LocalSky local = [&](const glm::dvec3& l) { return radianceOf({l.x, l.z, l.y}); };
    constexpr int kSamples = 256, kGrid = 16, kRays = kGrid * kGrid;
    std::printf("graded sky: roughness  view   reference  estimator  error      bound\n");
    for (const float roughness : {0.2f, 0.5f, 0.8f}) {
        TraceOptions opt;
        opt.mirrors = {plane};
        opt.sky = &sky;
        opt.mirrorRoughness = [roughness](ecs::Entity, glm::vec2) { return roughness; };
        opt.glossySamples = kSamples;
        const GroundTruthTracer tracer(reg, opt);
        for (const double viewDeg : {30.0, 75.0}) {
            const double cosV = std::cos(glm::radians(viewDeg));
            const double reference =
                reflectedOverHalfVectors(double(roughness) * roughness, cosV, 2048, 1024, local);
            const glm::vec3 v(float(std::sin(glm::radians(viewDeg))), float(cosV), 0.f);
            double sum = 0.0, sum2 = 0.0;
            for (int i = 0; i < kRays; ++i) {
                const glm::vec3 p(-1.f + 2.f * float(i % kGrid) / kGrid, 0.f,
                                  -1.f + 2.f * float(i / kGrid) / kGrid);
                const double c = tracer.radiance(p + v, -v).r;
                sum += c;
                sum2 += c * c;
            }
            const double mean = sum / kRays;
            // The kRays estimates are independent randomisations: their spread measures the
            // estimator's (a general bound, as in the furnace, would be 100x looser than the
            // effects it should catch). Five standard deviations of the mean, plus 1e-4 for
            // the sky's bilinear lookup and float sums.
            const double sdMean =
                std::sqrt(std::max(0.0, sum2 / kRays - mean * mean) / (kRays - 1));
            const double bound = 5.0 * sdMean + 1e-4;
            std::printf("            %9.2f  %4.0f   %9.6f  %9.6f  %+.2e  %.2e\n", roughness,
                        viewDeg, reference, mean, mean - reference, bound);
            EXPECT_NEAR(mean, reference, bound)
                << "roughness " << roughness << " view " << viewDeg << " deg";
        }
    }
}

} // namespace
} // namespace specula
