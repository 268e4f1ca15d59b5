// PEM maps of distance geometry (pem_distance_lookup.glsl.h: the distance flavour's secant
// search picks the texels, the map supplies the radiance): its weights against its radiance,
// the search against the closed-form box room, inference of an exactly representable map, the
// prior that unseen texels fall back to, and what bad input is refused as.
#include "assetcooker/lib/flavours/pem/pem_geometry.h"
#include "assetcooker/lib/flavours/pem/pem_infer.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/math/cube_face.h"
#include "pem_room.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <vector>

using namespace specula;
using namespace specula::test;

namespace {

glm::vec3 texelDirection(int t, int n) {
    const int face = t / (n * n), j = t / n % n, i = t % n;
    const glm::vec2 uv((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
    return glm::normalize(glsl::cubeFaceDirection(face, uv));
}

// The room's distance cube as a bake would store it: the distance from the centre to the
// wall through every texel centre, searched with the cooker's parameters.
std::shared_ptr<const PemDistanceGeometry> roomGeometry(int m) {
    auto g = std::make_shared<PemDistanceGeometry>();
    g->faceRes = m;
    g->dInf = 1000.f;
    for (int t = 0; t < PemMap::texelCount(m); ++t)
        g->distances.push_back(
            glm::length(exitPoint(glm::vec3(0.f), texelDirection(t, m), kRoomMin, kRoomMax)));
    choosePemDistanceSearch(*g);
    return g;
}

// A map whose texel t holds f(direction of t's centre).
PemMap mapOf(int n, std::shared_ptr<const PemDistanceGeometry> g,
             const std::function<glm::vec3(glm::vec3)>& f) {
    PemMap m{n, kRoomMin, kRoomMax, {}, std::move(g)};
    for (int t = 0; t < PemMap::texelCount(n); ++t)
        m.texels.push_back(f(texelDirection(t, n)));
    return m;
}

PemMap randomMap(int n, std::shared_ptr<const PemDistanceGeometry> g, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.1f, 0.9f);
    return mapOf(n, std::move(g), [&](glm::vec3) { return glm::vec3(u(rng), u(rng), u(rng)); });
}

// Reflector points about the centre (randomRays), targets left black.
PemSamples rays(int count, unsigned seed, float spread,
                const std::function<bool(glm::vec3)>& keep = nullptr) {
    return randomRays(count, seed, glm::vec3(0.f), spread, keep);
}

float angle(glm::vec3 a, glm::vec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.f, 1.f));
}

} // namespace

// The rendering matrix's rows: the recorded weights applied to the texels give the radiance
// the lookup computes, whichever texel the search ends on (or the ray's own direction).
TEST(PemDistanceLookup, WeightsReproduceRadiance) {
    PemWeights w;
    for (int m : {8, 64})
        for (int n : {1, 2, 5, 32}) {
            const PemMap map = randomMap(n, roomGeometry(m), 3u * unsigned(n + m));
            const PemLookupCpu lookup(map);
            PemSamples r = rays(3000, unsigned(n), 0.95f);
            for (int a = 0; a < 3; ++a) // along the axes from the centre
                for (float s : {-1.f, 1.f}) {
                    PemSample p;
                    p.l = glm::vec3(0.f);
                    p.l[a] = s;
                    r.push_back(p);
                }
            for (const PemSample& p : r) {
                expectWeightsReproduceRadiance(lookup, map, p.x, p.l, w);
                if (HasFatalFailure()) return;
            }
        }
}

// In a box room the distance cube holds the walls, so from off-centre points the search must
// land on the wall the ray really meets. A map holding its own texel directions makes the
// point found readable: its direction is the analytic hit's up to the distance cube's texel.
// A map holding the walls' radiance per direction (a capture at the centre) then gives the
// radiance at the true hit within the maps' bilinear error: the box lookup with the room's
// exact box is that error alone.
// The fetch count the bench reports: one map read for box geometry; for distance geometry the
// search's distance reads on top: at least one, at most the first-crossing march
// (glsl::kBracketSteps, issue 15) and one per step of its budget (the secant reads the cube
// once per step, then the map once). Before the march the cap was 1 + maxSteps.
TEST(PemDistanceLookup, TextureFetchesCountTheSearch) {
    const auto g = roomGeometry(32);
    const PemMap distanceMap = randomMap(16, g, 5u);
    const PemMap boxMap = randomMap(16, nullptr, 5u);
    const PemLookupCpu distance(distanceMap), box(boxMap);
    double mean = 0;
    const PemSamples r = rays(2000, 9u, 0.95f);
    for (const PemSample& p : r) {
        EXPECT_EQ(box.textureFetches(p.x, p.l), 1);
        const int f = distance.textureFetches(p.x, p.l);
        ASSERT_GE(f, 2);
        ASSERT_LE(f, 1 + glsl::kBracketSteps + g->maxSteps);
        mean += f;
    }
    std::printf("[pem fetches] distance geometry: %.2f fetches per lookup (max steps %d)\n",
                mean / double(r.size()), g->maxSteps);
}

TEST(PemDistanceLookup, BoxRoomSearchFindsTheWallHit) {
    const int m = 128, n = 64;
    const std::shared_ptr<const PemDistanceGeometry> geometry = roomGeometry(m);
    const PemSamples r = rays(4000, 9u, 0.8f);
    const PemMap dirs = mapOf(n, geometry, [](glm::vec3 d) { return 0.5f * d + glm::vec3(0.5f); });
    std::vector<float> err;
    float envmap = 0.f; // mean angle between the ray and its hit's direction: no parallax
    for (const PemSample& p : r) {
        const glm::vec3 hit = exitPoint(p.x, p.l, kRoomMin, kRoomMax);
        const glm::vec3 got = 2.f * PemLookupCpu(dirs).radiance(p.x, p.l) - glm::vec3(1.f);
        err.push_back(angle(got, hit));
        envmap += angle(p.l, hit) / float(r.size());
    }
    std::sort(err.begin(), err.end());
    const float texel = 2.f / float(m); // a texel's angle at a face centre (the largest)
    const float p50 = err[err.size() / 2], p99 = err[err.size() * 99 / 100];
    std::printf("[ figures  ] box room, distance cube %d: hit direction error median %.3g, "
                "99%% %.3g, worst %.3g texels; direction alone %.3g texels\n",
                m, double(p50 / texel), double(p99 / texel), double(err.back() / texel),
                double(envmap / texel));
    EXPECT_LT(p50, 0.25f * texel);
    EXPECT_LT(p99, texel);
    EXPECT_LT(err.back(), 2.f * texel);

    const PemMap walls = mapOf(n, geometry, [](glm::vec3 d) {
        return wallRadiance(exitPoint(glm::vec3(0.f), d, kRoomMin, kRoomMax));
    });
    PemMap box = walls;
    box.distance = nullptr; // the room's exact box: bilinear error only
    PemSamples targets = r;
    for (PemSample& p : targets)
        p.target = wallRadiance(exitPoint(p.x, p.l, kRoomMin, kRoomMax));
    const double distanceRms = rmsOn(walls, targets), boxRms = rmsOn(box, targets);
    std::printf("[ figures  ] box room, map %d: RMS against the true hit's radiance %.3g "
                "(exact box: %.3g)\n",
                n, distanceRms, boxRms);
    EXPECT_LT(distanceRms, 1.5 * boxRms);
}

// Targets the map can hold exactly (targets = A M): inference on the distance geometry finds
// a map whose lookups reproduce them, and the map carries the geometry.
TEST(PemDistanceInfer, ExactlyRepresentableTargetsAreReproduced) {
    const int n = 16;
    const std::shared_ptr<const PemDistanceGeometry> geometry = roomGeometry(64);
    const PemMap truth = randomMap(n, geometry, 5u);
    PemSamples samples = rays(12000, 3u, 0.9f);
    const PemLookupCpu lookup(truth);
    for (PemSample& p : samples)
        p.target = lookup.radiance(p.x, p.l);
    PemInferOptions o;
    o.faceRes = n;
    o.boxMin = kRoomMin;
    o.boxMax = kRoomMax;
    o.distance = geometry;
    o.regularisation = 1e-4f;
    o.tolerance = 1e-12;
    o.maxIterations = 20000;
    const PemInference r = inferPemMap(samples, o);
    std::printf("[ figures  ] distance geometry, exact targets, N=%d: RMS %.3g, %d unseen, "
                "iterations %d\n",
                n, r.residualRms, r.unseenTexels, r.iterations[0]);
    EXPECT_EQ(r.map.distance, geometry);
    EXPECT_NEAR(rmsOn(r.map, samples), r.residualRms, 1e-9);
    EXPECT_LT(r.residualRms, 1e-4);
}

// Rays that see only the lower part of the room leave most texels unseen. Without the
// smoothness rows a texel no sample reads appears in its prior row only, so it is its prior
// exactly; the texels the samples pin still follow them.
TEST(PemDistanceInfer, UnseenTexelsFallBackToThePrior) {
    const int n = 16;
    const std::shared_ptr<const PemDistanceGeometry> geometry = roomGeometry(64);
    PemSamples samples = rays(3000, 4u, 0.25f, [](glm::vec3 l) { return l.y < -0.3f; });
    for (PemSample& p : samples)
        p.target = wallRadiance(exitPoint(p.x, p.l, kRoomMin, kRoomMax));
    const PemMap captured = mapOf(n, geometry, [](glm::vec3 d) {
        return wallRadiance(exitPoint(glm::vec3(0.f), d, kRoomMin, kRoomMax));
    });
    PemInferOptions o;
    o.faceRes = n;
    o.distance = geometry;
    o.regularisation = 0.f;
    o.tolerance = 1e-10;
    o.maxIterations = 20000;
    o.prior = &captured.texels;
    o.priorWeight = 0.01f;
    const PemInference r = inferPemMap(samples, o);

    std::vector<char> seen(captured.texels.size(), 0);
    PemWeights w;
    const PemLookupCpu lookup(r.map);
    for (const PemSample& p : samples) {
        lookup.weights(p.x, p.l, w);
        for (const auto& [t, weight] : w)
            seen[std::size_t(t)] = 1;
    }
    float worst = 0.f;
    for (std::size_t t = 0; t < seen.size(); ++t)
        if (!seen[t]) worst = std::max(worst, glm::length(r.map.texels[t] - captured.texels[t]));
    std::printf("[ figures  ] prior: %d of %zu texels unseen, farthest from the prior by %.3g; "
                "sample RMS %.3g (the prior itself: %.3g)\n",
                r.unseenTexels, seen.size(), double(worst), r.residualRms,
                rmsOn(captured, samples));
    EXPECT_GT(r.unseenTexels, int(seen.size()) / 3);
    EXPECT_LT(worst, 1e-4f);
    EXPECT_LT(r.residualRms, 0.75 * rmsOn(captured, samples)); // the fit improves on it
}

TEST(PemDistanceInfer, BadGeometryOrPriorNamesTheField) {
    const PemSamples good = rays(50, 6u, 0.2f);
    auto expectField = [&](const PemInferOptions& o, const std::string& field) {
        try {
            inferPemMap(good, o);
            ADD_FAILURE() << "no error for " << field;
        } catch (const Error& e) {
            EXPECT_EQ(e.field(), field) << e.what();
        }
    };
    const std::shared_ptr<const PemDistanceGeometry> room = roomGeometry(8);
    auto withGeometry = [&](const std::function<void(PemDistanceGeometry&)>& edit) {
        auto g = std::make_shared<PemDistanceGeometry>(*room);
        edit(*g);
        PemInferOptions o;
        o.faceRes = 4;
        o.distance = g;
        return o;
    };
    expectField(withGeometry([](PemDistanceGeometry& g) { g.dInf = NAN; }), "distance.d_inf");
    expectField(withGeometry([](PemDistanceGeometry& g) { g.range = g.dInf; }), "distance.range");
    expectField(withGeometry([](PemDistanceGeometry& g) { g.tolerance = 0.f; }),
                "distance.tolerance");
    expectField(withGeometry([](PemDistanceGeometry& g) { g.maxSteps = 0; }), "distance.max_steps");
    expectField(withGeometry([](PemDistanceGeometry& g) { g.distances.pop_back(); }), "distance");
    expectField(withGeometry([](PemDistanceGeometry& g) { g.distances[7] = -1.f; }), "distance");
    expectField(withGeometry([](PemDistanceGeometry& g) { g.distances[7] = 2000.f; }), "distance");
    const std::vector<glm::vec3> wrongSize(5);
    PemInferOptions o;
    o.prior = &wrongSize;
    expectField(o, "prior");
    o.prior = nullptr;
    o.priorWeight = -1.f;
    expectField(o, "prior_weight");

    // A d_inf that a real distance would read as "nothing here" is refused by the cooker.
    PemDistanceGeometry g = *room;
    g.dInf = 6.f; // the room's far corners are about 4 m away
    try {
        choosePemDistanceSearch(g);
        ADD_FAILURE() << "no error for d_inf";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "d_inf") << e.what();
    }
}
