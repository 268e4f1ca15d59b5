#pragma once
// The closed-form room of the PEM tests (pem_infer_test, pem_distance_test): a box, probe-
// local, whose walls emit a smooth function of the point, and where a ray leaves it, computed
// apart from the shared lookups on purpose.
#include "assetcooker/lib/flavours/pem/pem_infer.h"
#include "components/reflection_probe/pem/pem_lookup_cpu.h"

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>

namespace specula::test {

// The room of the closed-form tests, probe-local; its walls emit a smooth function of the
// point (RGB in roughly [0.25, 0.85]).
inline const glm::vec3 kRoomMin(-2.f, -1.f, -3.f), kRoomMax(2.f, 1.5f, 3.f);

inline glm::vec3 wallRadiance(glm::vec3 p) {
    return {0.55f + 0.3f * std::sin(1.1f * p.x + 0.5f * p.z),
            0.5f + 0.25f * std::cos(0.8f * p.y - 0.6f * p.x),
            0.45f + 0.2f * std::sin(0.7f * p.z + 0.9f * p.y + 0.3f)};
}

// Where x + t l (x inside [lo, hi]) meets the box: the nearest of the six wall planes crossed
// ahead whose crossing lies on the wall. Written apart from the shared lookup on purpose.
inline glm::vec3 exitPoint(glm::vec3 x, glm::vec3 l, glm::vec3 lo, glm::vec3 hi) {
    float best = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a)
        for (float plane : {lo[a], hi[a]}) {
            if (l[a] == 0.f) continue;
            const float t = (plane - x[a]) / l[a];
            if (!(t > 0.f) || t >= best) continue;
            const glm::vec3 p = x + t * l;
            bool onWall = true;
            for (int b = 0; b < 3; ++b)
                if (b != a) onWall = onWall && p[b] >= lo[b] - 1e-4f && p[b] <= hi[b] + 1e-4f;
            if (onWall) best = t;
        }
    return x + best * l;
}

inline glm::vec3 randomDirection(std::mt19937& rng) {
    std::normal_distribution<float> g;
    for (;;) {
        const glm::vec3 v(g(rng), g(rng), g(rng));
        if (glm::length(v) > 1e-3f) return glm::normalize(v);
    }
}

// Reflector points in a cube of half-side `spread` around `centre`, directions uniform on
// the sphere (those `keep` accepts); targets left black.
inline PemSamples randomRays(int count, unsigned seed, glm::vec3 centre, float spread,
                             const std::function<bool(glm::vec3)>& keep = nullptr) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-spread, spread);
    PemSamples s;
    while (int(s.size()) < count) {
        PemSample p;
        p.x = centre + glm::vec3(u(rng), u(rng), u(rng));
        p.l = randomDirection(rng);
        if (!keep || keep(p.l)) s.push_back(p);
    }
    return s;
}

// One row of the rendering matrix against the lookup it comes from: 1 to 4 texels of one face
// (bilinear), positive weights summing to 1, and sum(weight * texel) = radiance(x, l).
inline void expectWeightsReproduceRadiance(const PemLookupCpu& lookup, const PemMap& map,
                                           glm::vec3 x, glm::vec3 l, PemWeights& w) {
    const int perFace = map.faceRes * map.faceRes;
    lookup.weights(x, l, w);
    ASSERT_GE(w.size(), 1u);
    ASSERT_LE(w.size(), 4u);
    glm::vec3 sum(0.f);
    float total = 0.f;
    for (const auto& [t, weight] : w) {
        ASSERT_GE(t, 0);
        ASSERT_LT(t, 6 * perFace);
        EXPECT_EQ(t / perFace, w.front().first / perFace); // bilinear within one face
        EXPECT_GT(weight, 0.f);
        total += weight;
        sum += weight * map.texels[std::size_t(t)];
    }
    EXPECT_NEAR(total, 1.f, 1e-6f);
    const glm::vec3 r = lookup.radiance(x, l);
    for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(sum[c], r[c], 2e-6f) << "face_res " << map.faceRes;
}

// RMS over RGB of the map's lookups at the samples against their targets.
inline double rmsOn(const PemMap& map, const PemSamples& samples) {
    const PemLookupCpu lookup(map);
    double sum = 0;
    for (const PemSample& p : samples) {
        const glm::dvec3 d = glm::dvec3(lookup.radiance(p.x, p.l)) - glm::dvec3(p.target);
        sum += glm::dot(d, d);
    }
    return std::sqrt(sum / (3.0 * double(samples.size())));
}

} // namespace specula::test
