// The peer, side by side (issue 15): the linear march with secant refinement of
// Szirmay-Kalos et al. 2005 (lookupMarch in shaders/distance_lookup.glsl.h) against the
// closed-form box room, beside Specula's bisection and secant searches at the same d_e.
// The hit each search proposes (CpuDistanceProbe::compositeHit, the shared code) is held
// to the analytic wall hit; the march may spend at most its steps and refinements.
#include "numerics_common.h"

#include <random>

using namespace specula;
using namespace specula::test;

namespace {

struct HitStats {
    std::vector<double> err; // |proposed hit point - analytic hit point|, metres
    long fetches = 0, maxFetches = 0, misses = 0, nonFinite = 0;
    double quantile(double q) {
        if (err.empty()) return 0.0;
        std::sort(err.begin(), err.end());
        return err[std::min(err.size() - 1, std::size_t(q * double(err.size())))];
    }
    double rms() const {
        double s = 0.0;
        for (double e : err)
            s += e * e;
        return err.empty() ? 0.0 : std::sqrt(s / double(err.size()));
    }
};

HitStats measure(const DistanceProbeAsset& a, DistanceMethod m, float de, int rays) {
    const DistanceLookupConfig cfg = configFor(a, m, de);
    const CpuDistanceProbe twin(a, cfg);
    std::mt19937 rng(2005);
    std::uniform_real_distribution<float> cell(-0.7f, 0.7f);
    std::normal_distribution<float> g;
    HitStats s;
    for (int i = 0; i < rays; ++i) {
        const glm::vec3 x(cell(rng), cell(rng), cell(rng));
        glm::vec3 d;
        do
            d = glm::vec3(g(rng), g(rng), g(rng));
        while (glm::dot(d, d) < 1e-6f);
        d = glm::normalize(d);
        const CpuDistanceProbe::CompositeHit h = twin.compositeHit(x, d);
        s.fetches += h.fetches;
        s.maxFetches = std::max(s.maxFetches, long(h.fetches));
        if (!h.hit) {
            ++s.misses; // the room is closed: every ray meets a wall
            continue;
        }
        const glm::vec3 got = x + h.t * d;
        const glm::vec3 want = x + room().exit(x, d) * d;
        if (!finite3(got)) {
            ++s.nonFinite;
            continue;
        }
        s.err.push_back(double(glm::length(got - want)));
    }
    return s;
}

} // namespace

TEST(DistanceMarch, HitsTheClosedFormWallWithinItsFetchCap) {
    const DistanceProbeAsset box = makeBoxProbe(room(), 256);
    constexpr int kRays = 20000;
    const long cap = glsl::kMarchSteps + glsl::kMarchRefineSteps + 1; // + the radiance fetch
    for (float de : {0.01f, 0.03f}) {
        for (DistanceMethod m :
             {DistanceMethod::Bisection, DistanceMethod::Secant, DistanceMethod::March}) {
            HitStats s = measure(box, m, de, kRays);
            const double p50 = s.quantile(0.5), p99 = s.quantile(0.99), worst = s.quantile(1.0);
            std::printf("[numerics] %-34s %-9s d_e=%-5g hit error median %.3e  p99 %.3e  "
                        "worst %.3e  rms %.3e m  fetches mean %.2f max %ld  misses %ld\n",
                        "march vs closed-form box room", toString(m), double(de), p50, p99, worst,
                        s.rms(), double(s.fetches) / kRays, s.maxFetches, s.misses);
            std::fflush(stdout);
            EXPECT_EQ(s.nonFinite, 0) << toString(m);
            if (m != DistanceMethod::March) continue;
            // The march's own properties: it never exceeds its steps and refinements, finds
            // every wall of the closed room, and lands on the analytic hit: the median within
            // d_e, 99 % within 5 d_e (grazing rays stop where the ray runs within d_e of
            // the wall, which moves the hit along it by up to d_e / cos).
            EXPECT_LE(s.maxFetches, cap);
            EXPECT_EQ(s.misses, 0);
            EXPECT_LE(p50, double(de));
            EXPECT_LE(p99, 5.0 * double(de));
        }
    }
}
