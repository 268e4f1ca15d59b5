// The active-set bounds of the PEM inference (issue 12, PemInferOptions::nonNegative): the
// unconstrained least squares drives texels below zero near sharp radiance steps, and
// clamping them afterwards spoils the fit. Checked here: no texel leaves its bound; where the
// unconstrained answer is already non-negative both modes give the same map; and where it is
// not, the bounded map fits the least-squares objective (data rows through the lookup twin,
// smoothness rows) no worse than the clamped unconstrained one.
#include "assetcooker/lib/flavours/pem/pem_infer.h"
#include "assetcooker/lib/flavours/pem/pem_layers.h"
#include "assetcooker/lib/bake/cook_settings_json.h"
#include "pem_room.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using namespace specula;
using namespace specula::test;

namespace {

PemInferOptions boxOptions(int n, glm::vec3 lo, glm::vec3 hi) {
    PemInferOptions o;
    o.faceRes = n;
    o.boxMin = lo;
    o.boxMax = hi;
    o.tolerance = 1e-10;
    o.maxIterations = 20000;
    return o;
}

// A room whose walls hold a bright patch on black: the step is what the smooth, bilinear map
// cannot follow, so the unconstrained least squares rings below zero beside it.
glm::vec3 patchRadiance(glm::vec3 p) {
    return p.x > 1.2f && p.y > 0.f ? glm::vec3(6.f, 3.f, 1.5f) : glm::vec3(0.02f);
}

// Rays from a small region, their targets the patch room where each leaves the true room;
// the map's box is smaller (approximate geometry), which the texels must absorb.
PemSamples patchSamples(int count, unsigned seed) {
    PemSamples s = randomRays(count, seed, glm::vec3(0.4f, 0.2f, -0.3f), 0.15f);
    for (PemSample& p : s)
        p.target = patchRadiance(exitPoint(p.x, p.l, kRoomMin, kRoomMax));
    return s;
}

// The least-squares objective inferPemMap minimises, computed apart from its matrix: each
// sample row through the lookup twin against its target, and lambda (t_a - t_b) over every
// neighbouring pair, summed over RGB (one level, no prior).
double objective(const PemMap& map, const PemSamples& samples, double lambda) {
    const PemLookupCpu lookup(map);
    double sum = 0;
    for (const PemSample& p : samples) {
        const glm::dvec3 d = glm::dvec3(lookup.radiance(p.x, p.l)) - glm::dvec3(p.target);
        sum += glm::dot(d, d);
    }
    for (const auto& [a, b] : pemNeighbourPairs(map.faceRes)) {
        const glm::dvec3 d = lambda * (glm::dvec3(map.texels[std::size_t(a)]) -
                                       glm::dvec3(map.texels[std::size_t(b)]));
        sum += glm::dot(d, d);
    }
    return sum;
}

void expectWithinBounds(const PemMap& map) {
    for (const glm::vec3& t : map.texels)
        for (int c = 0; c < 3; ++c)
            ASSERT_TRUE(t[c] >= 0.f) << t[c];
    for (const float a : map.alpha)
        ASSERT_TRUE(a >= 0.f && a <= 1.f) << a;
}

} // namespace

// A map in [0.1, 0.9] the samples see all over: the unconstrained answer is that map, above
// zero, so nothing is pinned and the bounded solve is the unconstrained one.
TEST(PemNonNegative, NonNegativeUnconstrainedSolutionIsKept) {
    const int n = 8;
    PemMap truth{n, kRoomMin, kRoomMax, std::vector<glm::vec3>(std::size_t(PemMap::texelCount(n))),
                 nullptr};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    for (glm::vec3& t : truth.texels)
        t = glm::vec3(u(rng), u(rng), u(rng));
    PemSamples samples = randomRays(3000, 12u, glm::vec3(0.f), 0.9f);
    const PemLookupCpu lookup(truth);
    for (PemSample& p : samples)
        p.target = lookup.radiance(p.x, p.l);
    PemInferOptions o = boxOptions(n, kRoomMin, kRoomMax);
    o.regularisation = 1e-3f;
    const PemInference off = inferPemMap(samples, o);
    o.nonNegative = true;
    const PemInference on = inferPemMap(samples, o);
    float worst = 0.f;
    for (std::size_t t = 0; t < truth.texels.size(); ++t)
        worst = std::max(worst, glm::length(on.map.texels[t] - off.map.texels[t]));
    std::printf("[ figures  ] non-negative map: %d re-solves, %d pinned, largest texel "
                "difference %.3g\n",
                on.boundPasses, on.pinnedTexels[0] + on.pinnedTexels[1] + on.pinnedTexels[2],
                worst);
    expectWithinBounds(on.map);
    EXPECT_EQ(on.boundPasses, 0);
    EXPECT_LT(worst, 1e-5f);
}

// The patch room: the unconstrained solve crosses zero; the bounded one pins those texels and
// refits the rest, so its objective is no larger than that of the clamped unconstrained map.
TEST(PemNonNegative, BoundedFitBeatsClampingTheUnconstrainedOne) {
    const int n = 8;
    const PemSamples samples = patchSamples(4000, 13u);
    PemInferOptions o = boxOptions(n, glm::vec3(-1.5f), glm::vec3(1.5f));
    const PemInference clamped = inferPemMap(samples, o);
    o.nonNegative = true;
    const PemInference bounded = inferPemMap(samples, o);
    const double lambda = double(o.regularisation);
    const double fClamped = objective(clamped.map, samples, lambda);
    const double fBounded = objective(bounded.map, samples, lambda);
    std::printf("[ figures  ] patch room N=%d: pinned R %d G %d B %d in %d re-solves; objective "
                "clamped %.6g, bounded %.6g; data RMS clamped %.4g, bounded %.4g\n",
                n, bounded.pinnedTexels[0], bounded.pinnedTexels[1], bounded.pinnedTexels[2],
                bounded.boundPasses, fClamped, fBounded, clamped.residualRms, bounded.residualRms);
    // The case must exercise the bounds: the unconstrained solve went below zero somewhere.
    ASSERT_GT(bounded.pinnedTexels[0] + bounded.pinnedTexels[1] + bounded.pinnedTexels[2], 0);
    expectWithinBounds(bounded.map);
    EXPECT_LE(fBounded, fClamped);
    EXPECT_LT(fBounded, 0.99 * fClamped);
}

// Deterministic: the same input gives the same bounded map, bit for bit.
TEST(PemNonNegative, BoundedSolveIsDeterministic) {
    const PemSamples samples = patchSamples(1500, 14u);
    PemInferOptions o = boxOptions(4, glm::vec3(-1.5f), glm::vec3(1.5f));
    o.nonNegative = true;
    const PemInference a = inferPemMap(samples, o), b = inferPemMap(samples, o);
    ASSERT_EQ(a.map.texels.size(), b.map.texels.size());
    for (std::size_t t = 0; t < a.map.texels.size(); ++t)
        EXPECT_EQ(a.map.texels[t], b.map.texels[t]) << t;
}

// The local layer's coverage is bounded on both sides: alpha stays in [0, 1], RGB >= 0.
TEST(PemNonNegative, LocalLayerStaysWithinItsBounds) {
    PemSamples samples = patchSamples(3000, 15u);
    for (std::size_t s = 0; s < samples.size(); ++s) {
        samples[s].onHull = false;
        samples[s].selfHit = samples[s].l.x > 0.3f; // a sharp coverage edge
        samples[s].distant = samples[s].selfHit ? glm::vec3(0.1f) : samples[s].target;
    }
    PemInferOptions o = boxOptions(8, glm::vec3(-1.5f), glm::vec3(1.5f));
    o.nonNegative = true;
    const PemLayers layers = inferPemLayers(samples, o, o, PemLocalSphere{glm::vec3(0.4f), 0.5f});
    expectWithinBounds(layers.distant.map);
    expectWithinBounds(layers.local.map);
    std::printf("[ figures  ] local layer refit: pinned RGB %d %d %d\n",
                layers.local.pinnedTexels[0], layers.local.pinnedTexels[1],
                layers.local.pinnedTexels[2]);
}

// The setting reaches a shard's settings and comes back (shard_settings.cpp lists every PEM
// field), both ways.
TEST(PemNonNegative, SettingRoundTripsThroughShardSettings) {
    for (const bool on : {false, true}) {
        PemCookSettings s;
        s.nonNegative = on;
        const nlohmann::json j = cookSettingsToJson(CookFlavour{s});
        EXPECT_EQ(j.at("non_negative").get<bool>(), on);
        const CookFlavour back = cookSettingsFromJson(j, "settings.json");
        EXPECT_EQ(std::get<PemCookSettings>(back).nonNegative, on);
    }
}
