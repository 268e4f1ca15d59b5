// Where layered mode's per-layer search loses (issue 15, item 3). The error budget found
// layered's error dominated by its search (room +5.9 dB, bowl_room +6.7 dB with an exact one).
// Each reflector pixel of the room and the bowl room is traced with Embree (environment only,
// what the probe holds) and looked up by the layered twin as the shader runs and with the
// exact first-crossing search; every ray the two disagree on is put down to the object layer
// that decides it (the exact winner the lookup missed or placed elsewhere, or a layer whose
// false hit beat it), by that layer's method and by how often its f = stored distance - |l|
// changes sign inside the layer's box span (sampled densely with the twin's nearest-texel
// fetch).
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/image/sampling.h"
#include "engine/math/cube_face.h"
#include "engine/raytrace/ground_truth.h"
#include "support/lookup_config.h"
#include "support/mirror_rays.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace specula;
using namespace specula::test;

namespace {

constexpr int kWidth = 640, kHeight = 480, kFaceRes = 256;
constexpr int kDense = 1000; // samples of f over a layer's box span

struct Ray {
    glm::vec3 x, lhat, truth;
};

struct Scene {
    std::string name, dir;
    DistanceProbeAsset asset;
    std::vector<Ray> rays;
};

Scene cookAndTrace(const std::string& name, const std::string& gltf) {
    ProbeRoom room(gltf);
    Scene s;
    s.name = name;
    s.dir = (std::filesystem::temp_directory_path() /
             ("specula-layered-search-" + name + "-" + std::to_string(::getpid())))
                .string();
    DistanceCookSettings cs;
    cs.faceRes = kFaceRes;
    cs.planned = cs.recordPlan = false; // one layer per object, methods by solid angle
    CookOptions o;
    o.out = s.dir;
    o.flavour = cs;
    o.progress = false;
    cookProbe(room.probeScene(), o, nullptr);
    s.asset = readDistanceProbe(s.dir + "/manifest.json");
    const TraceOptions opts = groundTruthOptions(room.probeScene(), true);
    const GroundTruthTracer tracer(room.registry(), opts);
    const CameraView cam = room.camera(kWidth, kHeight);
    for (const test::MirrorRay& m : test::mirrorRays(tracer, opts, cam))
        s.rays.push_back({m.position - s.asset.centre, m.dir, m.env.radiance});
    return s;
}

DistanceLookupConfig layeredConfig(const DistanceProbeAsset& a, DistanceMethod layerMethod,
                                   float de) {
    return test::lookupConfigOf(a, DistanceMethod::Layered, de, layerMethod);
}

// Sign changes of f over [t0, t1] (d_inf counts as f > 0, as the searches read it).
int signChanges(const DistanceProbeAsset& a, int layer, glm::vec3 x, glm::vec3 lhat, float t0,
                float t1) {
    int changes = 0;
    bool prevPositive = true;
    for (int k = 0; k <= kDense; ++k) {
        const glm::vec3 l = x + (t0 + (t1 - t0) * float(k) / float(kDense)) * lhat;
        const glm::vec3 f = glsl::cubeFaceUv(l);
        const float d = sampleNearest(a.layers[std::size_t(layer)].faces[std::size_t(f.z)],
                                      glm::vec2(f.x, f.y), Wrap::Clamp)
                            .a;
        const bool positive = d - glm::length(l) > 0.f;
        if (k > 0 && positive != prevPositive) ++changes;
        prevPositive = positive;
    }
    return changes;
}

// The ray's stretch inside layer i's box (the slab test); enter > leave when it misses.
glm::vec2 boxSpan(const DistanceLookupConfig& c, int i, glm::vec3 x, glm::vec3 lhat) {
    float enter = 0.f, leave = 1e30f;
    for (int k = 0; k < 3; ++k) {
        const float inv = 1.f / (std::abs(lhat[k]) > 1e-12f ? lhat[k] : 1e-12f);
        float a = (c.layers[i].boxMin[k] - x[k]) * inv, b = (c.layers[i].boxMax[k] - x[k]) * inv;
        if (a > b) std::swap(a, b);
        enter = std::max(enter, a), leave = std::min(leave, b);
    }
    return {enter, std::min(leave, 2.f * c.params.range)};
}

double squared(glm::vec3 a, glm::vec3 b) {
    const glm::vec3 d = a - b;
    return double(glm::dot(d, d));
}

const char* methodName(int glslIndex) {
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.glslIndex == glslIndex) return row.label.name;
    return "?";
}

struct Outcome {
    double psnr = 0, psnrExact = 0, fetches = 0;
    double searchShare = 0; // the search term's share of the squared error
    double multiShare = 0;  // its share held by rays whose layer's f crosses more than once
};

// The layered lookup with `layerMethod` on every object layer (Envmap: the cooked methods)
// against its exact search over the same rays, the disagreements by cause on stdout.
Outcome diagnose(const Scene& s, DistanceMethod layerMethod, float de) {
    const DistanceLookupConfig c = layeredConfig(s.asset, layerMethod, de);
    CpuDistanceProbe twin(s.asset, c), exact(s.asset, c);
    exact.setExperiment({true, false});
    const float tol = 5.f * de;
    struct Cause {
        int rays = 0;
        double loss = 0; // base squared error less the exact search's
    };
    std::map<std::string, Cause> causes;
    double sse = 0, sseExact = 0, loss = 0, lossMulti = 0;
    long fetches = 0;
    int disagree = 0;
    for (const Ray& r : s.rays) {
        const CpuDistanceProbe::CompositeHit b = twin.lookupHit(r.x, r.lhat);
        const CpuDistanceProbe::CompositeHit e = exact.lookupHit(r.x, r.lhat);
        fetches += b.fetches;
        const double eb = squared(b.radiance, r.truth), ee = squared(e.radiance, r.truth);
        sse += eb, sseExact += ee;
        if (b.hit == e.hit && (!b.hit || std::abs(b.t - e.t) <= tol)) continue;
        ++disagree;
        // The deciding layer: the exact winner where the lookup got it wrong, else the layer
        // whose hit beat it.
        int culprit = 0;
        std::string kind;
        for (int i = 1; i <= c.params.layerCount && !culprit; ++i) {
            const auto hb = twin.objectLayerHit(i, r.x, r.lhat);
            const auto he = exact.objectLayerHit(i, r.x, r.lhat);
            if (e.hit && he.hit && std::abs(he.t - e.t) <= 1e-4f * std::max(1.f, e.t)) {
                if (!hb.hit)
                    culprit = i, kind = "missed";
                else if (hb.t > he.t + tol)
                    culprit = i, kind = "later";
                else if (hb.t < he.t - tol)
                    culprit = i, kind = "earlier";
            } else if (hb.hit && (!e.hit || hb.t < e.t - tol)) {
                culprit = i, kind = "false hit";
            }
        }
        int changes = 0;
        std::string key = "unattributed";
        if (culprit) {
            const glm::vec2 span = boxSpan(c, culprit, r.x, r.lhat);
            changes = signChanges(s.asset, culprit, r.x, r.lhat, span.x, span.y);
            key = std::string(methodName(c.layers[culprit].method)) + " layer, " + kind +
                  ", f sign changes " + (changes > 2 ? std::string("3+") : std::to_string(changes));
        }
        causes[key].rays += 1;
        causes[key].loss += eb - ee;
        loss += eb - ee;
        if (changes > 1) lossMulti += eb - ee;
    }
    const double n = double(s.rays.size());
    Outcome o;
    o.psnr = -10.0 * std::log10(sse / (3.0 * n));
    o.psnrExact = -10.0 * std::log10(sseExact / (3.0 * n));
    o.fetches = double(fetches) / n;
    o.searchShare = (sse - sseExact) / sse;
    o.multiShare = loss > 0 ? lossMulti / loss : 0.0;
    std::printf("%s layered (%s layers) d_e %.2f: %zu rays, %.2f dB at %.2f fetches a ray, exact "
                "%.2f dB; %d rays disagree (%.1f %%), search term %.1f %% of the SSE\n",
                s.name.c_str(),
                layerMethod == DistanceMethod::Envmap ? "cooked" : toString(layerMethod),
                double(de), s.rays.size(), o.psnr, o.fetches, o.psnrExact, disagree,
                100.0 * disagree / n, 100.0 * (sse - sseExact) / sse);
    for (const auto& [key, cause] : causes)
        std::printf("    %-48s %5d rays (%.2f %%), %6.1f %% of the search term\n", key.c_str(),
                    cause.rays, 100.0 * cause.rays / n, loss > 0 ? 100.0 * cause.loss / loss : 0.0);
    std::fflush(stdout);
    return o;
}

} // namespace

TEST(LayeredSearch, WhereObjectLayersLoseTheFirstCrossing) {
    for (const auto& [name, gltf] :
         {std::pair<std::string, std::string>{"room", kRoomScene},
          {"bowl_room", SPECULA_SOURCE_DIR "/assets/bowl_room/bowl_room.gltf"}}) {
        const Scene s = cookAndTrace(name, gltf);
        ASSERT_GT(s.rays.size(), 5000u) << name;
        // The cooked methods (average distance on the small layers, bisection on the large),
        // as the bench's layered row runs them. Measured before the average-distance point
        // moved onto the layer's box span (issue 15), room / bowl_room: 31.63 / 30.38 dB
        // against 37.34 / 36.44 with the exact search, the search term 73 % / 75 % of the
        // squared error, 96 % / 102 % of it on rays whose small object the fetch at x + d-bar
        // l-hat missed; 1.74 / 1.75 fetches a ray.
        const Outcome cooked = diagnose(s, DistanceMethod::Envmap, 0.01f);
        EXPECT_LT(cooked.searchShare, 0.25) << name;
        EXPECT_LT(cooked.fetches, 1.8) << name << ": the fix adds no fetch";
        // Bisection on every layer, for comparison: where f crosses zero more than once in
        // one layer's box span is where a search over the span can settle on a later
        // crossing; that holds little of the error on these scenes.
        const Outcome bisection = diagnose(s, DistanceMethod::Bisection, 0.01f);
        EXPECT_LT(bisection.searchShare * bisection.multiShare, 0.05) << name;
        std::filesystem::remove_all(s.dir);
    }
}
