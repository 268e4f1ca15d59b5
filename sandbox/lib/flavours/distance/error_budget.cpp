#include "sandbox/lib/flavours/distance/error_budget.h"

#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/raytrace/ground_truth.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace specula {

namespace {

// The ground truth's push off a mirror along its geometric normal (ground_truth.cpp): the
// same origin, so the reflected ray meets what the truth's met.
float offsetEpsilon(glm::vec3 p) {
    const float m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z), 1.f});
    return 1e-4f * m;
}

double squaredError(glm::vec3 c, glm::vec3 truth) {
    const glm::dvec3 d = glm::dvec3(c) - glm::dvec3(truth);
    return glm::dot(d, d);
}

// Summed squared errors of the budget's lookups: the 8 combinations of the lookup
// experiments (index bit 0 exact search, bit 1 same-surface radiance, bit 2 faces 2x), then
// the same with the hidden rays' errors left out (kSeen + combination), the oracle, and the
// count of hidden rays, the baseline on every layer stored as half floats, and on every layer
// compressed (BC6H radiance, half distance).
constexpr std::size_t kSeen = 8, kOracle = 16, kHidden = 17, kHalf = 18, kBc6h = 19, kLookups = 20;
using Sums = std::array<double, kLookups>;

} // namespace

std::vector<BudgetRay> traceBudgetRays(ReflectionScene& scene, const CameraView& camera,
                                       const Image& mask, const Image& envTruth, glm::vec3 centre) {
    const GroundTruthTracer tracer(scene.registry(), groundTruthOptions(scene.probeScene(), true));
    std::vector<BudgetRay> rays;
    for (int y = 0; y < mask.height; ++y)
        for (int x = 0; x < mask.width; ++x) {
            if (mask.at(x, y)[0] < 0.5f) continue;
            glm::vec3 origin, dir;
            camera.primaryRay(x, y, origin, dir);
            const std::optional<Hit> hit = tracer.fullScene().intersect(origin, dir);
            if (!hit || !tracer.options().mirrors.contains(hit->entity)) continue;
            // Mirror about the shading normal turned to the viewer, as the truth does.
            const glm::vec3 d = glm::normalize(dir);
            const glm::vec3 n = glm::dot(hit->normal, d) > 0.f ? -hit->normal : hit->normal;
            const glm::vec3 ng = glm::dot(hit->geometricNormal, d) > 0.f ? -hit->geometricNormal
                                                                         : hit->geometricNormal;
            BudgetRay r;
            r.l = glm::normalize(glm::reflect(d, n));
            const glm::vec3 next = hit->position + offsetEpsilon(hit->position) * ng;
            const EnvSample env = tracer.traceEnvironment(next, r.l);
            r.x = hit->position - centre;
            r.truth = glm::vec3(envTruth.rgba(x, y));
            r.hasHit = env.hit;
            if (env.hit) r.hit = next + env.distance * r.l - centre;
            rays.push_back(r);
        }
    return rays;
}

double MethodErrorBudget::interaction() const {
    auto z = [](double v) { return std::isnan(v) ? 0.0 : v; };
    return base - all - termSearch() - z(termResolution()) - termSilhouettes() - termDisocclusion();
}

std::string MethodErrorBudget::dominant() const {
    const std::array<std::pair<double, const char*>, 4> terms = {{
        {termSearch(), "search"},
        {std::isnan(res2x) ? -1e300 : termResolution(), "resolution"},
        {termSilhouettes(), "silhouettes"},
        {termDisocclusion(), "disocclusion"},
    }};
    const auto top = std::max_element(
        terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    // Nothing to remove (a lookup that matches the truth) or no experiment that helps.
    return top->first > 0 ? top->second : "none";
}

double psnrOfMse(double mse) {
    if (std::isnan(mse)) return mse;
    return mse > 0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity();
}

StoredProbeVariants storedProbeVariants(const DistanceProbeAsset& asset) {
    StoredProbeVariants v{std::nullopt, asset};
    if (allLayersFitHalf(asset)) {
        v.half = asset;
        roundAllLayersToHalf(*v.half);
    }
    roundTripLayersThroughBc6h(v.bc6h);
    return v;
}

MethodErrorBudget measureErrorBudget(const std::vector<BudgetRay>& rays,
                                     const DistanceProbe& settings, const DistanceProbeAsset& asset,
                                     const DistanceProbeAsset* asset2x,
                                     const StoredProbeVariants* stored) {
    const DistanceLookupConfig config = makeLookupConfig(settings, asset);
    const DistanceLookupConfig config2x =
        asset2x ? makeLookupConfig(settings, *asset2x) : DistanceLookupConfig{};
    // (e) RGBA16F: the composite as well as the object layers rounded to half floats, where
    // every layer's values are normal halves (allLayersFitHalf); (f) compressed: every layer's
    // radiance through BC6H, its distance as half floats.
    std::optional<StoredProbeVariants> made;
    if (!stored) stored = &made.emplace(storedProbeVariants(asset));
    const std::optional<DistanceProbeAsset>& halfAsset = stored->half;
    const DistanceProbeAsset& bc6hAsset = stored->bc6h;
    const DistanceLookupConfig halfConfig =
        halfAsset ? makeLookupConfig(settings, *halfAsset) : DistanceLookupConfig{};
    const DistanceLookupConfig bc6hConfig = makeLookupConfig(settings, bc6hAsset);
    // Deterministic: the same rays sum in the same order, so two budgets compare exactly.
    const Sums sums = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, rays.size(), 256), Sums{},
        [&](const tbb::blocked_range<std::size_t>& range, Sums s) {
            // One twin per combination of the lookup experiments (bit 0 exact search, bit 1
            // same-surface radiance, bit 2 faces 2x), per task: a twin notes per lookup
            // whether the sky answered, so two threads never share one.
            std::array<std::optional<CpuDistanceProbe>, 8> twins;
            for (int c = 0; c < 8; ++c) {
                if ((c & 4) && !asset2x) continue;
                twins[std::size_t(c)].emplace(c & 4 ? *asset2x : asset, c & 4 ? config2x : config);
                twins[std::size_t(c)]->setExperiment({(c & 1) != 0, (c & 2) != 0});
            }
            const CpuDistanceProbe& base = *twins[0];
            std::optional<CpuDistanceProbe> half;
            if (halfAsset) half.emplace(*halfAsset, halfConfig);
            const CpuDistanceProbe bc6h(bc6hAsset, bc6hConfig);
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const BudgetRay& r = rays[i];
                // A ray that leaves for the sky is always seen: the probe keeps the sky apart.
                const CpuDistanceProbe::CentreView v =
                    r.hasHit ? base.centreView(r.hit) : CpuDistanceProbe::CentreView{};
                const bool hidden = r.hasHit && !v.seen;
                const bool hidden2x =
                    asset2x && r.hasHit ? !twins[4]->centreView(r.hit).seen : hidden;
                for (int c = 0; c < 8; ++c) {
                    if (!twins[std::size_t(c)]) continue;
                    int fetches = 0;
                    const double e =
                        squaredError(twins[std::size_t(c)]->radiance(r.x, r.l, fetches), r.truth);
                    s[std::size_t(c)] += e;
                    if (!((c & 4) ? hidden2x : hidden)) s[kSeen + std::size_t(c)] += e;
                }
                s[kHidden] += hidden ? 1.0 : 0.0;
                if (half) {
                    int fetches = 0;
                    s[kHalf] += squaredError(half->radiance(r.x, r.l, fetches), r.truth);
                }
                int fetches = 0;
                s[kBc6h] += squaredError(bc6h.radiance(r.x, r.l, fetches), r.truth);
                const glm::vec3 oracle = r.hasHit ? v.radiance : base.sky(r.l);
                s[kOracle] += squaredError(oracle, r.truth);
            }
            return s;
        },
        [](Sums a, const Sums& b) {
            for (std::size_t i = 0; i < a.size(); ++i)
                a[i] += b[i];
            return a;
        });
    MethodErrorBudget b;
    b.rays = rays.size();
    const double n = rays.empty() ? 1.0 : 3.0 * double(rays.size()); // RGB values
    b.base = sums[0] / n;
    b.exact = sums[1] / n;
    b.sameSurface = sums[2] / n;
    b.seen = sums[kSeen] / n;
    b.oracle = sums[kOracle] / n;
    if (halfAsset) b.halfFloat = sums[kHalf] / n;
    b.bc6h = sums[kBc6h] / n;
    const std::size_t cubes = asset.layers.size();
    b.bytesFloat = cubes * cubeBytesRgba32f(asset.faceRes);
    b.bytesHalf = cubes * cubeBytesRgba16f(asset.faceRes);
    b.bytesBc6h = cubes * cubeBytesBc6hR16f(asset.faceRes);
    if (asset2x) b.res2x = sums[4] / n;
    b.all = sums[kSeen + (asset2x ? 7 : 3)] / n;
    // The residual: the least any combination of the experiments leaves.
    b.residual = b.base;
    for (int c = 0; c < 8; ++c)
        for (int seen = 0; seen < 2; ++seen) {
            if ((c & 4) && !asset2x) continue;
            const double mse = sums[std::size_t(c) + (seen ? kSeen : 0)] / n;
            if (mse >= b.residual) continue;
            b.residual = mse;
            b.residualSet.clear();
            const char* names[] = {"search", "silhouettes", "resolution"};
            for (int k = 0; k < 3; ++k)
                if (c & (1 << k))
                    b.residualSet += std::string(b.residualSet.empty() ? "" : "+") + names[k];
            if (seen)
                b.residualSet += std::string(b.residualSet.empty() ? "" : "+") + "disocclusion";
        }
    if (b.residualSet.empty()) b.residualSet = "none";
    b.hiddenShare = rays.empty() ? 0.0 : sums[kHidden] / double(rays.size());
    return b;
}

} // namespace specula
