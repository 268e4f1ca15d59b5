// Which crossing the searches find. Along a reflected ray x + t lhat (probe-local) the
// distance probe's f(t) = stored distance(x + t lhat) - |x + t lhat| is > 0 before the
// surface and < 0 beyond it; where the ray passes behind a nearer object as seen from the
// centre, f changes sign more than once and only the first + to - change is the surface the
// ray meets. The room's reflector pixels are traced with Embree (environment only, what the
// probe holds) and f is sampled densely along each reflected ray with the same nearest-texel
// fetch the twin reads, so each search's hit can be told apart as "the first crossing",
// "a later crossing" or "elsewhere".
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/image/sampling.h"
#include "engine/math/cube_face.h"
#include "engine/raytrace/ground_truth.h"
#include "support/composite_probe.h"
#include "support/lookup_config.h"
#include "support/mirror_rays.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace specula;
using namespace specula::test;

namespace {

constexpr int kWidth = 160, kHeight = 120, kFaceRes = 64;
constexpr int kDense = 2000; // samples of f along (0, 2D]

struct Ray {
    glm::vec3 x, lhat;
    float tTrue;     // Embree's hit along the reflected ray (probe-local, from x)
    glm::vec3 truth; // Embree's radiance
    bool hit;
};

struct Fixture {
    ProbeRoom scene;
    DistanceProbeAsset asset;
    std::vector<Ray> rays;

    Fixture() {
        asset = cookedCompositeProbe(scene, kFaceRes, "specula-first-crossing");

        const TraceOptions opts = groundTruthOptions(scene.probeScene(), true);
        const GroundTruthTracer tracer(scene.registry(), opts);
        const CameraView cam = scene.camera(kWidth, kHeight);
        for (const test::MirrorRay& m : test::mirrorRays(tracer, opts, cam))
            rays.push_back(
                {m.position - asset.centre, m.dir, m.env.distance, m.env.radiance, m.env.hit});
    }

    // The twin's distance fetch: the composite's nearest texel.
    float stored(glm::vec3 l) const {
        const glm::vec3 f = glsl::cubeFaceUv(l);
        return sampleNearest(asset.layers[0].faces[std::size_t(f.z)], glm::vec2(f.x, f.y),
                             Wrap::Clamp)
            .a;
    }
};

Fixture& fixture() {
    static Fixture f;
    return f;
}

DistanceLookupConfig configOf(const DistanceProbeAsset& a, DistanceMethod m, float de) {
    return test::lookupConfigOf(a, m, de);
}

} // namespace

TEST(DistanceFirstCrossing, WhereTheSearchesMissTheFirstCrossing) {
    Fixture& fx = fixture();
    ASSERT_GT(fx.rays.size(), 500u);
    const DistanceLookupConfig base = configOf(fx.asset, DistanceMethod::Bisection, 0.01f);
    const float D = base.params.range;
    const float dInf = base.params.dInf;

    // Per ray: the sign changes of f over the dense samples, and the first + to - change
    // (the first crossing; d_inf counts as f > 0).
    struct Dense {
        int changes = 0;
        float tFirst = -1.f;
    };
    std::vector<Dense> dense(fx.rays.size());
    int multi = 0;
    for (std::size_t i = 0; i < fx.rays.size(); ++i) {
        const Ray& r = fx.rays[i];
        float prev = 1.f;
        float tPrev = 0.f;
        for (int k = 1; k <= kDense; ++k) {
            const float t = 2.f * D * float(k) / float(kDense);
            const glm::vec3 l = r.x + t * r.lhat;
            const float f = fx.stored(l) - glm::length(l);
            if ((f > 0.f) != (prev > 0.f)) {
                ++dense[i].changes;
                if (f <= 0.f && dense[i].tFirst < 0.f) dense[i].tFirst = 0.5f * (t + tPrev);
            }
            prev = f;
            tPrev = t;
        }
        if (dense[i].changes > 1) ++multi;
    }
    std::printf("room: %zu reflector rays, D = %.3f, d_inf = %.1f; f changes sign more than once "
                "on %d (%.1f %%)\n",
                fx.rays.size(), D, dInf, multi, 100.0 * multi / double(fx.rays.size()));

    for (const float de : {0.1f, 0.01f}) {
        const float tol = 5.f * de;
        std::vector<CpuDistanceProbe::CompositeHit> march(fx.rays.size());
        long marchFetches = 0;
        {
            const CpuDistanceProbe twin(fx.asset, configOf(fx.asset, DistanceMethod::March, de));
            for (std::size_t i = 0; i < fx.rays.size(); ++i) {
                march[i] = twin.compositeHit(fx.rays[i].x, fx.rays[i].lhat);
                marchFetches += march[i].fetches;
            }
        }
        auto right = [&](const CpuDistanceProbe::CompositeHit& h, const Ray& r) {
            if (!r.hit) return !h.hit;
            return h.hit && std::abs(h.t - r.tTrue) <= tol;
        };
        for (const DistanceMethod m :
             {DistanceMethod::Bisection, DistanceMethod::Secant, DistanceMethod::March}) {
            const CpuDistanceProbe twin(fx.asset, configOf(fx.asset, m, de));
            long fetches = 0;
            int wrong = 0, wrongMulti = 0, wrongMultiMarchRight = 0, laterCrossing = 0;
            int wrongSingle = 0, wrongDenseAlsoWrong = 0;
            double sse = 0.0, sseWrong = 0.0, sseMulti = 0.0;
            for (std::size_t i = 0; i < fx.rays.size(); ++i) {
                const Ray& r = fx.rays[i];
                const CpuDistanceProbe::CompositeHit h = twin.compositeHit(r.x, r.lhat);
                fetches += h.fetches;
                const glm::vec3 e = h.radiance - r.truth;
                const double e2 = double(glm::dot(e, e));
                sse += e2;
                if (right(h, r)) continue;
                ++wrong;
                sseWrong += e2;
                const Dense& dn = dense[i];
                const bool denseRight =
                    r.hit ? dn.tFirst >= 0.f && std::abs(dn.tFirst - r.tTrue) <= tol
                          : dn.tFirst < 0.f;
                if (!denseRight) ++wrongDenseAlsoWrong;
                if (dn.changes > 1) {
                    ++wrongMulti;
                    sseMulti += e2;
                    if (right(march[i], r)) ++wrongMultiMarchRight;
                    if (h.hit && dn.tFirst >= 0.f && h.t > dn.tFirst + tol) ++laterCrossing;
                } else {
                    ++wrongSingle;
                }
            }
            const double n = double(fx.rays.size());
            std::printf("d_e %.2f %-9s fetches/ray %.2f  wrong (> 5 d_e) %d (%.1f %%): f with > 1 "
                        "sign change %d (%.1f %% of wrong; march right on %d, hit beyond the "
                        "first crossing %d), single %d; dense first crossing also wrong %d. "
                        "RGB SSE %.2f, of it wrong %.1f %%, multi %.1f %%\n",
                        de, toString(m), double(fetches) / n, wrong, 100.0 * wrong / n, wrongMulti,
                        wrong ? 100.0 * wrongMulti / wrong : 0.0, wrongMultiMarchRight,
                        laterCrossing, wrongSingle, wrongDenseAlsoWrong, sse,
                        sse > 0 ? 100.0 * sseWrong / sse : 0.0,
                        sse > 0 ? 100.0 * sseMulti / sse : 0.0);
            std::fflush(stdout);
            if (m == DistanceMethod::March) continue;
            // Measured before the first-crossing march (issue 15), d_e 0.1 / 0.01: the rays
            // whose f changes sign more than once held 55 % / 58 % of bisection's squared
            // error (and secant's), at 6.1 / 9.4 fetches a ray (march: 25.6 / 26.5).
            // With 8 bracket points: 8 % / 18 %, at 11.1 / 14.3 (secant 10.5 / 12.0); with
            // 20 (kBracketSteps since the full-size diagnosis, distance_bracket_diagnosis_test)
            // more fetches, still fewer than the peer's: the goal is its error in fewer.
            EXPECT_LT(sseMulti, 0.25 * sse) << toString(m) << " d_e " << de;
            EXPECT_LT(fetches, marchFetches) << toString(m) << " d_e " << de;
        }
    }
}

// Where a search ends on a surface texel, it has either converged (the stored distance agrees
// with |l| within d_e) or it has located a crossing within d_e along the ray: f changes sign
// within d_e of the end point. Bisection holds this by construction (its bracket halves every
// step). Secant held it only while its false-position steps kept up: on the nearest-texel
// staircase an Illinois secant can creep towards one end of its bracket and run out of steps
// far from the crossing (issue 15); Dekker's safeguard (a midpoint after any step that did not
// halve the bracket, 2N steps at most) gives it bisection's guarantee.
TEST(DistanceFirstCrossing, SearchesEndWithinTheToleranceOfACrossing) {
    Fixture& fx = fixture();
    ASSERT_GT(fx.rays.size(), 500u);
    constexpr int kAround = 512; // samples of f over [t_end - d_e, t_end + d_e]
    for (const float de : {0.1f, 0.03f, 0.01f}) {
        for (const DistanceMethod m : {DistanceMethod::Bisection, DistanceMethod::Secant}) {
            const CpuDistanceProbe twin(fx.asset, configOf(fx.asset, m, de));
            int ended = 0, far = 0;
            for (const Ray& r : fx.rays) {
                const CpuDistanceProbe::CompositeHit h = twin.compositeHit(r.x, r.lhat);
                if (!h.hit) continue;
                ++ended;
                const float tEnd = glm::dot(h.at - r.x, r.lhat);
                const float fEnd = fx.stored(h.at) - glm::length(h.at);
                if (std::abs(fEnd) < de) continue;
                bool changes = false;
                for (int k = 0; k <= kAround && !changes; ++k) {
                    const float t = tEnd - de + 2.f * de * float(k) / float(kAround);
                    const glm::vec3 l = r.x + t * r.lhat;
                    changes = (fx.stored(l) - glm::length(l) > 0.f) != (fEnd > 0.f);
                }
                if (!changes) ++far;
            }
            std::printf("d_e %.2f %-9s: %d of %d hits ended neither converged nor within d_e of "
                        "a crossing\n",
                        de, toString(m), far, ended);
            EXPECT_GT(ended, 400) << toString(m) << " d_e " << de;
            EXPECT_EQ(far, 0) << toString(m) << " d_e " << de;
        }
    }
}
