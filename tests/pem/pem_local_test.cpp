// The local layer of the two-layer PEM (issue 12): its sphere lookup against a closed-form
// intersection and GL_LINEAR sampling, its weights against its radiance (linearity, alpha
// included), the sphere fit, and the composite inference on a case the two layers represent
// exactly while one map cannot.
#include "assetcooker/lib/flavours/pem/pem_layers.h"
#include "engine/core/glsl_host.h" // glm, which sampling.h expects
#include "engine/image/sampling.h"
#include "engine/math/cube_face.h"
#include "pem_fixtures.h"
#include "pem_room.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

using namespace specula;
using namespace specula::test;

namespace {

// Where x + t l meets the sphere last (t > 0, the larger root), in double: written apart from
// the shared lookup. Only called for rays that cross the sphere.
glm::vec3 farPoint(glm::vec3 x, glm::vec3 l, const PemLocalSphere& s) {
    const glm::dvec3 o = glm::dvec3(x) - glm::dvec3(s.centre), d(l);
    const double b = glm::dot(o, d), q = glm::dot(o, o) - double(s.radius) * double(s.radius);
    const double t = -b + std::sqrt(b * b - q);
    return glm::vec3(glm::dvec3(x) + t * d);
}

// Rays from points inside the sphere (any direction) and from outside aimed through it.
std::vector<std::pair<glm::vec3, glm::vec3>> sphereRays(const PemLocalSphere& s, int count) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    std::vector<std::pair<glm::vec3, glm::vec3>> rays;
    while (int(rays.size()) < count) {
        const glm::vec3 p = s.centre + 1.6f * s.radius * glm::vec3(u(rng), u(rng), u(rng));
        glm::vec3 l = randomDirection(rng);
        if (glm::length(p - s.centre) > s.radius) {
            // Aim at a point well inside, so the ray crosses the sphere.
            const glm::vec3 aim = s.centre + 0.5f * s.radius * randomDirection(rng);
            l = glm::normalize(aim - p);
        }
        rays.emplace_back(p, l);
    }
    return rays;
}

} // namespace

TEST(PemLocalLookup, FarSphereIntersectionAndGlLinearSampling) {
    const PemLocalSphere sphere{{0.3f, -0.2f, 0.1f}, 0.45f};
    for (int n : {1, 4, 32}) {
        const PemMap map = randomLocal(n, sphere, 3u + unsigned(n));
        std::array<Image, 6> faces; // the local map as six RGBA images, sampled as GL_LINEAR
        for (int f = 0; f < 6; ++f) {
            faces[std::size_t(f)] = Image(n, n, 4);
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const std::size_t t = std::size_t((f * n + j) * n + i);
                    for (int c = 0; c < 3; ++c)
                        faces[std::size_t(f)].at(i, j)[c] = map.texels[t][c];
                    faces[std::size_t(f)].at(i, j)[3] = map.alpha[t];
                }
        }
        const PemLookupCpu lookup(map);
        for (const auto& [x, l] : sphereRays(sphere, 3000)) {
            const glm::vec3 p = farPoint(x, l, sphere);
            ASSERT_NEAR(glm::length(p - sphere.centre), sphere.radius, 1e-5f);
            const glm::vec3 f = glsl::cubeFaceUv(p - sphere.centre);
            const glm::vec4 want =
                sampleBilinear(faces[std::size_t(f.z)], glm::vec2(f.x, f.y), Wrap::Clamp);
            const glm::vec4 got = lookup.localRadiance(x, l);
            ASSERT_LT(glm::length(got - want), 2e-4f) << "n " << n;
            ASSERT_EQ(lookup.radiance(x, l), glm::vec3(got)) << "radiance: premultiplied RGB";
        }
    }
}

TEST(PemLocalLookup, WeightsReproduceRadianceAndAlpha) {
    const PemLocalSphere sphere{{-0.1f, 0.05f, 0.2f}, 0.6f};
    PemWeights w;
    for (int n : {1, 2, 5, 32}) {
        const PemMap map = randomLocal(n, sphere, 17u * unsigned(n));
        const PemLookupCpu lookup(map);
        for (const auto& [x, l] : sphereRays(sphere, 2000)) {
            expectWeightsReproduceRadiance(lookup, map, x, l, w);
            if (HasFatalFailure()) return;
            float alpha = 0.f;
            for (const auto& [t, weight] : w)
                alpha += weight * map.alpha[std::size_t(t)];
            ASSERT_NEAR(alpha, lookup.localRadiance(x, l).a, 2e-6f);
        }
    }
}

TEST(PemLocalSphereFit, RecoversASphereFromPointsOnPartOfIt) {
    // A bowl's inside: the lower half of a sphere, seen through an opening.
    const PemLocalSphere truth{{0.2f, -0.05f, 0.4f}, 0.45f};
    std::mt19937 rng(3);
    std::vector<glm::vec3> points;
    while (points.size() < 2000) {
        const glm::vec3 d = randomDirection(rng);
        if (d.y < -0.1f) points.push_back(truth.centre + truth.radius * d);
    }
    const PemLocalSphere fit = fitPemLocalSphere(points);
    EXPECT_LT(glm::length(fit.centre - truth.centre), 1e-4f);
    EXPECT_NEAR(fit.radius, truth.radius, 1e-4f);
    // The bounding sphere of the same points is not the bowl's: its centre sits lower.
    const PemLocalSphere bound = boundPemLocalSphere(points);
    EXPECT_GT(glm::length(bound.centre - truth.centre), 0.1f);

    // Coplanar points (a flat mirror) fall back to the bounding sphere.
    std::vector<glm::vec3> flat;
    for (int i = 0; i < 100; ++i)
        flat.emplace_back(float(i % 10) * 0.1f, 0.5f, float(i / 10) * 0.1f);
    const PemLocalSphere f = fitPemLocalSphere(flat);
    EXPECT_EQ(f, boundPemLocalSphere(flat));
    EXPECT_NEAR(f.radius, std::sqrt(2.f) * 0.45f, 1e-5f);
}

// Rays leaving a mirror bowl's inside (points on the lower half of the local sphere, heading
// inwards). By construction a ray sees the bowl again exactly when the direction from the
// sphere's centre to its far hit lies on the cube's -Y face, and then its target is the true
// local map there (alpha 1, premultiplied = radiance), else the true distant box map: the
// two-layer model holds every target exactly (texels never mix alpha 0 and 1: bilinear
// stays within a face).
TEST(PemLayersInfer, TwoLayersReproduceWhatOneMapCannot) {
    const int n = 6;
    const PemLocalSphere sphere{{0.f, -0.2f, 0.f}, 0.5f};
    PemMap distantTruth = {n, kRoomMin, kRoomMax, {}, nullptr};
    PemMap localTruth = randomLocal(n, sphere, 41);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    for (int t = 0; t < PemMap::texelCount(n); ++t)
        distantTruth.texels.emplace_back(u(rng), u(rng), u(rng));
    for (int t = 0; t < PemMap::texelCount(n); ++t) {
        const bool bowl = t / (n * n) == 3; // -Y
        localTruth.alpha[std::size_t(t)] = bowl ? 1.f : 0.f;
        localTruth.texels[std::size_t(t)] =
            bowl ? glm::vec3(u(rng), u(rng), u(rng)) : glm::vec3(0.f);
    }
    const PemLookupCpu distant(distantTruth), local(localTruth);
    PemSamples samples;
    std::size_t self = 0;
    while (samples.size() < 30000) {
        PemSample s;
        glm::vec3 d = randomDirection(rng);
        if (d.y > -0.05f) continue;
        s.x = sphere.centre + sphere.radius * d;
        s.l = randomDirection(rng);
        if (glm::dot(s.l, d) > -0.05f) continue; // inwards
        const glm::vec3 hit = farPoint(s.x, s.l, sphere);
        s.selfHit = int(glsl::cubeFaceUv(hit - sphere.centre).z) == 3;
        s.onHull = false;
        s.distant = distant.radiance(s.x, s.l);
        s.target = s.selfHit ? glm::vec3(local.localRadiance(s.x, s.l)) : s.distant;
        self += s.selfHit;
        samples.push_back(s);
    }
    PemInferOptions o;
    o.faceRes = n;
    o.boxMin = kRoomMin;
    o.boxMax = kRoomMax;
    o.regularisation = 0.f; // the exact solution, not a smoothed one
    o.tolerance = 1e-10;
    const PemLayers layers = inferPemLayers(samples, o, o, sphere);
    const PemLookupCpu d2(layers.distant.map), l2(layers.local.map);
    double layered = 0, single = 0;
    const PemInference one = inferPemMap(samples, o); // today's single map on the full targets
    const PemLookupCpu m1(one.map);
    for (const PemSample& s : samples) {
        const glm::vec4 over = l2.localRadiance(s.x, s.l);
        const glm::vec3 c = glm::vec3(over) + (1.f - over.a) * d2.radiance(s.x, s.l);
        layered += glm::dot(glm::dvec3(c - s.target), glm::dvec3(c - s.target));
        const glm::vec3 e = m1.radiance(s.x, s.l) - s.target;
        single += glm::dot(glm::dvec3(e), glm::dvec3(e));
    }
    const double rmsLayered = std::sqrt(layered / (3.0 * double(samples.size())));
    const double rmsSingle = std::sqrt(single / (3.0 * double(samples.size())));
    std::printf("two layers vs one map on %zu rays (%zu see the bowl): RMS %.2e vs %.2e\n",
                samples.size(), self, rmsLayered, rmsSingle);
    ASSERT_GT(self, samples.size() / 20);
    ASSERT_LT(self, samples.size() / 2);
    EXPECT_LT(rmsLayered, 1e-4);
    EXPECT_GT(rmsSingle, 100.0 * rmsLayered);
    EXPECT_GT(rmsSingle, 0.02);
}

TEST(PemLayersInfer, HullRaysStayOutOfTheLocalRows) {
    PemSamples samples(50);
    std::mt19937 rng(1);
    for (PemSample& s : samples) {
        s.x = glm::vec3(0.1f);
        s.l = randomDirection(rng);
        s.target = s.distant = glm::vec3(0.5f);
        s.selfHit = true; // would pull alpha to 1, were it read
        s.onHull = true;
    }
    PemInferOptions o;
    o.faceRes = 4;
    o.boxMin = kRoomMin;
    o.boxMax = kRoomMax;
    const PemLayers layers = inferPemLayers(samples, o, o, {glm::vec3(0.f), 1.f});
    const PemCoverage c = pemCoverage(samples);
    EXPECT_EQ(c.offHull, 0u);
    EXPECT_EQ(c.selfHits, 0u);
    ASSERT_EQ(layers.local.map.alpha.size(), std::size_t(PemMap::texelCount(4)));
    for (float a : layers.local.map.alpha)
        ASSERT_EQ(a, 0.f);
}
