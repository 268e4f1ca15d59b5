// The bench's error budget (sandbox/lib/flavours/distance/error_budget.h) on closed-form scenes
// whose terms are known: an empty box room (the centre sees every wall point, no depth
// discontinuity: no disocclusion, no silhouette term) and the same room with a ball in it (walls
// behind the ball hidden from the centre: disocclusion). The rays' truth is the closed-form
// reflection.
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "probe/analytic_probe.h"
#include "sandbox/lib/flavours/distance/error_budget.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>

using namespace specula;
using namespace specula::test;

namespace {

struct Ball {
    glm::vec3 c{1.6f, 0.2f, 0.3f};
    float r = 0.6f;
    // Nearest hit along unit d from x outside the ball.
    std::optional<float> hit(glm::vec3 x, glm::vec3 d) const {
        const glm::vec3 o = x - c;
        const float b = glm::dot(o, d), q = glm::dot(o, o) - r * r, disc = b * b - q;
        if (disc < 0.f || q < 0.f) return std::nullopt;
        const float t = -b - std::sqrt(disc);
        return t > 0.f ? std::optional<float>(t) : std::nullopt;
    }
};

// The exact scene: the box, and the ball when given. Returns the distance along d.
float traceScene(const AnalyticBox& box, const std::optional<Ball>& ball, glm::vec3 x,
                 glm::vec3 d) {
    float t = box.exit(x, d);
    if (ball)
        if (const auto tb = ball->hit(x, d)) t = std::min(t, *tb);
    return t;
}

// The composite of the scene baked from the centre in closed form at n^2 faces.
DistanceProbeAsset bakeScene(const AnalyticBox& box, const std::optional<Ball>& ball, int n) {
    DistanceProbeAsset a;
    a.faceRes = n;
    a.dInf = 1000.f;
    a.boxMin = box.lo;
    a.boxMax = box.hi;
    DistanceProbeLayer L = bakeAnalyticLayer("scene", n, a.dInf, [&](glm::vec3 d) {
        const float t = traceScene(box, ball, glm::vec3(0.f), d);
        return std::pair(t, AnalyticBox::radianceAt(t * d));
    });
    L.avgDistance = 4.f;
    L.solidAngle = 12.566f;
    a.range = 0.5f * (L.maxDistance + 1.f) * 1.05f;
    a.layers.push_back(L);
    return a;
}

// Reflector points within 0.7 m of the centre, directions uniform on the sphere; the truth
// traced exactly.
std::vector<BudgetRay> makeRays(const AnalyticBox& box, const std::optional<Ball>& ball,
                                int count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    std::vector<BudgetRay> rays;
    while (int(rays.size()) < count) {
        BudgetRay r;
        r.x = 0.7f * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d(u(rng), u(rng), u(rng));
        if (glm::dot(d, d) > 1.f || glm::dot(d, d) < 1e-4f) continue;
        if (ball && glm::length(r.x - ball->c) <= ball->r) continue;
        r.l = glm::normalize(d);
        const float t = traceScene(box, ball, r.x, r.l);
        r.hit = r.x + t * r.l;
        r.hasHit = true;
        r.truth = AnalyticBox::radianceAt(r.hit);
        rays.push_back(r);
    }
    return rays;
}

DistanceProbe settingsOf(DistanceMethod m, float de) {
    DistanceProbe p;
    p.method = m;
    p.errorTolerance = de;
    return p;
}

void print(const char* what, const MethodErrorBudget& b) {
    std::printf("[budget] %s: base %.4g (%.2f dB), search %.3g, resolution %.3g, silhouettes "
                "%.3g, disocclusion %.3g, residual %.3g, oracle %.3g, hidden %.3f, dominant %s\n",
                what, b.base, psnrOfMse(b.base), b.termSearch(), b.termResolution(),
                b.termSilhouettes(), b.termDisocclusion(), b.all, b.oracle, b.hiddenShare,
                b.dominant().c_str());
}

const AnalyticBox kBox;

TEST(ErrorBudget, EmptyBoxHasNoDisocclusionNorSilhouetteTerm) {
    const DistanceProbeAsset a = bakeScene(kBox, std::nullopt, 32);
    const DistanceProbeAsset a2 = bakeScene(kBox, std::nullopt, 64);
    const std::vector<BudgetRay> rays = makeRays(kBox, std::nullopt, 4000);
    for (DistanceMethod m : {DistanceMethod::Envmap, DistanceMethod::Bisection,
                             DistanceMethod::Secant, DistanceMethod::March}) {
        const MethodErrorBudget b = measureErrorBudget(rays, settingsOf(m, 0.01f), a, &a2);
        print(toString(m), b);
        EXPECT_GT(b.base, 0.0);
        // Every wall point is in the centre's view: nothing hidden, the term exactly 0.
        EXPECT_EQ(b.hiddenShare, 0.0);
        EXPECT_EQ(b.termDisocclusion(), 0.0);
        // Distances are continuous over the box (its edges included): the same four texels
        // weigh the radiance, only the summation order differs.
        EXPECT_NEAR(b.termSilhouettes(), 0.0, 1e-5 * b.base);
        // Four times the texels: a finer copy of the same smooth walls, for every method
        // that finds the wall point (envmap's error is parallax, which no texel removes).
        if (m != DistanceMethod::Envmap) {
            EXPECT_GT(b.termResolution(), 0.0);
        }
        // The oracle (the truth's hit looked up) leaves the texture's own error only.
        EXPECT_LT(b.oracle, b.base);
    }
    // Envmap ignores parallax: the exact search along the stored distances removes nearly
    // all of its error, which is what it is made of.
    const MethodErrorBudget env =
        measureErrorBudget(rays, settingsOf(DistanceMethod::Envmap, 0.01f), a, &a2);
    EXPECT_EQ(env.dominant(), "search");
    EXPECT_LT(env.exact, 0.1 * env.base);
}

TEST(ErrorBudget, SearchTermVanishesWhenTheToleranceDoes) {
    const DistanceProbeAsset a = bakeScene(kBox, std::nullopt, 32);
    const std::vector<BudgetRay> rays = makeRays(kBox, std::nullopt, 4000);
    for (DistanceMethod m : {DistanceMethod::Bisection, DistanceMethod::Secant}) {
        const MethodErrorBudget coarse = measureErrorBudget(rays, settingsOf(m, 0.3f), a, nullptr);
        const MethodErrorBudget fine = measureErrorBudget(rays, settingsOf(m, 1e-5f), a, nullptr);
        print((std::string(toString(m)) + " d_e 0.3").c_str(), coarse);
        print((std::string(toString(m)) + " d_e 1e-5").c_str(), fine);
        // The exact search is what both converge to: the same figure whatever d_e.
        EXPECT_DOUBLE_EQ(coarse.exact, fine.exact);
        EXPECT_GT(coarse.termSearch(), 0.0);
        // At d_e 1e-5 both land on a crossing of the same stored (nearest-texel) distances;
        // they differ only where that staircase crosses more than once within a texel of the
        // wall, the exact search taking the first: a small fraction of d_e 0.3's term.
        EXPECT_GT(coarse.termSearch(), 10.0 * std::abs(fine.termSearch()));
        // Without the faces 2x, res2x is missing, not zero, and the term is NaN.
        EXPECT_TRUE(std::isnan(fine.res2x) && std::isnan(fine.termResolution()));
    }
}

TEST(ErrorBudget, OccluderShowsDisocclusion) {
    const Ball ball;
    const DistanceProbeAsset a = bakeScene(kBox, ball, 32);
    const DistanceProbeAsset a2 = bakeScene(kBox, ball, 64);
    const std::vector<BudgetRay> rays = makeRays(kBox, ball, 4000);
    const MethodErrorBudget empty = measureErrorBudget(makeRays(kBox, std::nullopt, 4000),
                                                       settingsOf(DistanceMethod::Bisection, 0.01f),
                                                       bakeScene(kBox, std::nullopt, 32), nullptr);
    const MethodErrorBudget b =
        measureErrorBudget(rays, settingsOf(DistanceMethod::Bisection, 0.01f), a, &a2);
    print("bisection, ball", b);
    // Some reflector points see wall behind the ball, which the centre cannot.
    EXPECT_GT(b.hiddenShare, 0.0);
    EXPECT_GT(b.termDisocclusion(), 0.0);
    EXPECT_EQ(empty.termDisocclusion(), 0.0);
    // The oracle cannot recover what the centre does not hold.
    EXPECT_GT(b.oracle, 0.0);
}

TEST(ErrorBudget, ExperimentsOffIsTheShadersLookup) {
    const DistanceProbeAsset a = bakeScene(kBox, Ball{}, 32);
    const std::vector<BudgetRay> rays = makeRays(kBox, Ball{}, 500);
    for (DistanceMethod m : {DistanceMethod::Bisection, DistanceMethod::March}) {
        const DistanceLookupConfig c = makeLookupConfig(settingsOf(m, 0.01f), a);
        const CpuDistanceProbe plain(a, c);
        CpuDistanceProbe reset(a, c);
        reset.setExperiment({true, true});
        reset.setExperiment({});
        for (const BudgetRay& r : rays) {
            int f1 = 0, f2 = 0;
            const glm::vec3 p = plain.radiance(r.x, r.l, f1), q = reset.radiance(r.x, r.l, f2);
            ASSERT_EQ(p, q);
            ASSERT_EQ(f1, f2);
        }
    }
}

} // namespace
