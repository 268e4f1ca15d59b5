// Where bisection and secant on the composite lose to the march, the peer (issue 15): the
// shared lookup compiled here over the composite alone, so the bracket the searches start
// from (bracketFirstCrossing) can be told apart from the search inside it. Each reflector
// ray's error against Embree is split into what the exact first crossing (lookupExact)
// leaves and the excess of the method's search over it, and rays are sorted by what the
// bracket saw: converged on a march point, crossed with the exact crossing inside, crossed
// beyond a first crossing it stepped over, no crossing seen while the exact search found one
// (missed), or the sky both ways. Printed per category; asserted: bisection and secant
// reach the march's error (within 5 % of its MSE, 0.2 dB) in fewer fetches.
//
// The room at 160x120 with 64^2 faces by default; SPECULA_DIAG_SCENE (room | truck_room),
// SPECULA_DIAG_SIZE (WxH) and SPECULA_DIAG_FACES set another (1024x768 and 256: the full
// bench's size, where the diagnosis behind kBracketSteps = 20 was made).
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"
#include "engine/math/cube_face.h"
#include "engine/math/shading.h"
#include "engine/raytrace/ground_truth.h"
#include "support/composite_probe.h"
#include "support/lookup_config.h"
#include "support/mirror_rays.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace specula::glsl {
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
struct DiagFetches {
    const DistanceProbeAsset* asset = nullptr;
    const Image& face(vec3 dir, vec2& uv) const {
        const vec3 f = cubeFaceUv(dir);
        uv = vec2(f.x, f.y);
        return asset->layers[0].faces[std::size_t(f.z)];
    }
    float fetchDistance(int, vec3 dir) const {
        vec2 uv;
        const Image& img = face(dir, uv);
        return sampleNearest(img, uv, Wrap::Clamp).a;
    }
    vec3 fetchRadiance(int, vec3 dir) const {
        vec2 uv;
        const Image& img = face(dir, uv);
        return vec3(sampleBilinear(img, uv, Wrap::Clamp));
    }
    vec3 fetchSky(vec3 dir) const {
        if (asset->sky.empty()) return vec3(0.f);
        return vec3(sampleBilinear(asset->sky, equirectUv(dir), Wrap::Repeat, Wrap::Clamp));
    }
    bool exactSearchOn() const { return false; }
    float layerAvgDistance(int) const { return 0.f; }
};
#define HAS_ENVMAP 0
#define HAS_BOXPROJ 0
#define HAS_BISECTION 1
#define HAS_SECANT 1
#define HAS_AVGDIST 0
#define HAS_MARCH 1
#define HAS_LAYERS 0
#define SPECULA_EXACT_SEARCH_HOOK
struct DiagTwin : DiagFetches {
#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
};
} // namespace specula::glsl

using namespace specula;

namespace {

std::string env(const char* name, const char* fallback) {
    const char* v = std::getenv(name);
    return v && *v ? v : fallback;
}

DistanceLookupConfig configOf(const DistanceProbeAsset& a, DistanceMethod m, float de) {
    return test::lookupConfigOf(a, m, de);
}

} // namespace

TEST(DistanceBracketDiagnosis, ErrorByBracketOutcome) {
    const std::string sceneName = env("SPECULA_DIAG_SCENE", "room");
    int width = 160, height = 120;
    std::sscanf(env("SPECULA_DIAG_SIZE", "160x120").c_str(), "%dx%d", &width, &height);
    const int faces = std::atoi(env("SPECULA_DIAG_FACES", "64").c_str());

    test::ProbeRoom scene(std::string(SPECULA_SOURCE_DIR) + "/assets/" + sceneName + "/" +
                          sceneName + ".gltf");
    const DistanceProbeAsset asset =
        test::cookedCompositeProbe(scene, faces, "specula-bracket-diag");

    const TraceOptions opts = groundTruthOptions(scene.probeScene(), true);
    const GroundTruthTracer tracer(scene.registry(), opts);
    const auto rays = test::mirrorRays(tracer, opts, scene.camera(width, height));
    std::printf("%s %dx%d faces %d: %zu rays\n", sceneName.c_str(), width, height, faces,
                rays.size());

    glsl::DiagTwin tw;
    tw.asset = &asset;
    enum { kConv, kInside, kSteppedOver, kBeyond, kMissed, kSky, kCats };
    const char* catName[kCats] = {"converged",    "inside", "stepped-over",
                                  "exact-beyond", "missed", "sky"};
    for (const float de : {0.1f, 0.01f}) {
        const glsl::DistanceParams p = configOf(asset, DistanceMethod::Bisection, de).params;
        const glsl::DiagTwin::RaySpan span = tw.makeSpan(0.f, 2.f * p.range, p.maxSteps);
        // Per ray: the exact first crossing and the bracket's outcome.
        std::vector<int> cat(rays.size());
        std::vector<glm::vec3> truth(rays.size()), xs(rays.size());
        std::vector<double> e2Exact(rays.size());
        double sseExact = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const glm::vec3 x = rays[i].position - asset.centre, l = rays[i].dir;
            xs[i] = x;
            truth[i] = rays[i].env.radiance;
            const glsl::LayerHit ex = tw.lookupExact(0, x, l, p, span);
            const glm::vec3 re = ex.hit ? ex.radiance : tw.fetchSky(l);
            e2Exact[i] = double(glm::dot(re - truth[i], re - truth[i]));
            sseExact += e2Exact[i];
            const glsl::DiagTwin::Bracket b =
                tw.bracketFirstCrossing(0, x, l, p, span, glsl::kBracketSteps);
            if (b.converged) {
                cat[i] = kConv;
            } else if (b.crossed) {
                cat[i] = !ex.hit            ? kBeyond
                         : ex.t < b.ta - de ? kSteppedOver
                         : ex.t > b.tb + de ? kBeyond
                                            : kInside;
            } else {
                cat[i] = ex.hit ? kMissed : kSky;
            }
        }
        const double n = double(rays.size());
        std::printf("d_e %.2f: exact-search MSE %.5f (PSNR %.2f)\n", de, sseExact / n,
                    -10.0 * std::log10(sseExact / n / 3.0));
        double mse[3] = {}, perRay[3] = {};
        const int methods[3] = {glsl::kMethodMarch, glsl::kMethodBisection, glsl::kMethodSecant};
        for (int mi = 0; mi < 3; ++mi) {
            const int method = methods[mi];
            double sse = 0, excess[kCats] = {}, sseCat[kCats] = {};
            int count[kCats] = {};
            long fetches = 0;
            for (std::size_t i = 0; i < rays.size(); ++i) {
                const glsl::LayerHit h = tw.lookupLayer(method, 0, xs[i], rays[i].dir, p, span);
                fetches += h.fetches;
                const glm::vec3 r = h.hit ? h.radiance : tw.fetchSky(rays[i].dir);
                const double e2 = double(glm::dot(r - truth[i], r - truth[i]));
                sse += e2;
                excess[cat[i]] += e2 - e2Exact[i];
                sseCat[cat[i]] += e2;
                ++count[cat[i]];
            }
            std::printf("  %-9s MSE %.5f (PSNR %.2f) fetches %.2f; search excess over exact "
                        "%.1f %% of its SSE\n",
                        method == glsl::kMethodBisection ? "bisection"
                        : method == glsl::kMethodSecant  ? "secant"
                                                         : "march",
                        sse / n, -10.0 * std::log10(sse / n / 3.0), double(fetches) / n,
                        100.0 * (sse - sseExact) / sse);
            mse[mi] = sse / n;
            perRay[mi] = double(fetches) / n;
            for (int c = 0; c < kCats; ++c)
                std::printf("    %-17s rays %6d (%5.1f %%)  SSE share %5.1f %%  excess share of "
                            "SSE %6.1f %%\n",
                            catName[c], count[c], 100.0 * count[c] / n, 100.0 * sseCat[c] / sse,
                            100.0 * excess[c] / sse);
        }
        // The goal of issue 15: the peer's error in fewer fetches. Measured with 20 bracket
        // points and the safeguarded secant, MSE over the march's, bisection / secant, d_e 0.1
        // and 0.01: 0.96 / 0.92, 1.02 / 1.00 here; at full size (1024x768, 256^2) room 1.01 /
        // 1.00, 0.92 / 0.94; truck_room 1.08 / 1.08, 0.95 / 0.95; bowl_room 1.12 / 1.08, 1.00 /
        // 1.00 (at d_e 0.1 the march's 30 points see thin objects the 20 do not).
        for (int mi = 1; mi < 3; ++mi) {
            EXPECT_LT(perRay[mi], perRay[0]) << "method " << methods[mi] << " d_e " << de;
            EXPECT_LT(mse[mi], 1.05 * mse[0]) << "method " << methods[mi] << " d_e " << de;
        }
    }
}
