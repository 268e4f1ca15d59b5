#include "assetcooker/lib/flavours/pem/pem_samples.h"

#include "assetcooker/lib/flavours/pem/pem_bake.h"
#include "assetcooker/lib/flavours/pem/pem_layers.h"
#include "components/reflection_probe/pem/pem_blend.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/scene/mesh_bounds.h"

#include <functional>
#include <limits>
#include <optional>

namespace specula {

namespace {

// Each sample's fit half-way to the next one: the two maps blended as the runtime blends them
// (pemBlend; on the walk's closed loops the last sample blends with the first, on the open
// camera path it has no next one: NaN) against the tracer at that viewpoint.
void measureOffManifold(const PemAsset& asset, const PemCookSettings& s, const PemCookHooks& hooks,
                        const std::string& file,
                        const std::function<std::optional<PemSamples>(float)>& trace) {
    std::vector<float> params;
    for (const PemSampleMap& m : asset.samples)
        params.push_back(m.parameter);
    const bool periodic = pemPathClosed(s);
    for (int k = 0; k < s.samples; ++k) {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(file, "cancelled", "the bake was cancelled");
        const float t = 0.5f * (pemSampleParameter(s, k) + pemSampleParameter(s, k + 1));
        // Nothing to measure past an open path's end, or where the camera sees no reflector.
        const std::optional<PemSamples> seen =
            !periodic && k + 1 == s.samples ? std::nullopt : trace(t);
        if (!seen) {
            (*hooks.fits)[std::size_t(k)].psnrOff = std::numeric_limits<double>::quiet_NaN();
            continue;
        }
        const PemBlendWeights w = pemBlend(params, t, false, periodic);
        // The runtime's own twin: the blend, and the local layer off the hull.
        glsl::PemParams block = pemParams(asset, PemProbe{});
        block.layerA = 6 * w.a;
        block.layerB = 6 * w.b;
        block.wb = w.wb;
        const PemProbeCpu twin(asset, block);
        (*hooks.fits)[std::size_t(k)].psnrOff = pemSamplesPsnr(
            *seen,
            [&](const PemSample& p) { return twin.radiance(p.x, p.l, p.onHull, p.footprint()); },
            pemRows(s));
        if (hooks.progress) hooks.progress(0.5 + 0.5 * double(k + 1) / double(s.samples));
    }
}

// One sample's maps as the runtime draws them at that sample: the distant map, with the
// local layer over it off the hull.
glm::vec3 sampleRadiance(const PemSampleMap& m, bool localLayer, const PemSample& p) {
    const glm::vec3 distant = PemLookupCpu(m.map).radiance(p.x, p.l, p.footprint());
    if (!localLayer || p.onHull) return distant;
    const glm::vec4 local = PemLookupCpu(m.local).localRadiance(p.x, p.l);
    return glm::vec3(local) + (1.f - local.a) * distant;
}

} // namespace

Aabb pemMapBox(const ProbeScene& scene, glm::vec3 centre) {
    Aabb box = Aabb::cube(centre, 0.5f * markupCellSize(scene.markup));
    for (ecs::Entity e : scene.loaded.entities)
        if (!scene.markup.mirrorEntities.contains(e))
            box.extend(meshWorldBounds(scene.registry, e));
    return box.translated(-centre);
}

PemAsset cookPemAsset(ProbeScene& scene, const PemCookSettings& s, const PemCookHooks& hooks) {
    PemBake bake(scene, s, hooks.centre);
    if (hooks.fits) hooks.fits->clear();
    // The inference's share of the bar; the off-manifold measurement traces once more.
    const double share = hooks.fits ? 0.5 : 1.0;
    auto pollCancel = [&] {
        if (hooks.cancelled && hooks.cancelled())
            throw Error(scene.path, "cancelled", "the bake was cancelled");
    };
    // Every sample traced first: "auto" decides on the local layer from all of them. A sample
    // whose view holds no reflector pixel (a camera path that looks away) is left out: the
    // runtime blends its neighbours across the gap (pemBlend reads each sample's parameter).
    std::vector<PemSamples> traced; // the samples seen, in order
    std::vector<int> tracedIndex;   // sample k's in traced; -1: left out
    for (int k = 0; k < s.samples; ++k) {
        pollCancel();
        std::optional<PemSamples> seen = bake.traceAt(bake.parameter(k));
        tracedIndex.push_back(seen ? int(traced.size()) : -1);
        if (seen) traced.push_back(std::move(*seen));
        if (hooks.progress) hooks.progress(share * 0.5 * double(k + 1) / double(s.samples));
    }
    if (traced.empty()) bake.trace(0); // throws, naming the sample and the camera
    const PemLocalDecision decision = decidePemLocalLayer(s, traced);
    std::vector<PemSampleMap> maps;
    for (int k = 0; k < s.samples; ++k) {
        pollCancel();
        PemSampleFit fit;
        fit.parameter = bake.parameter(k);
        fit.localLayer = decision.local;
        if (tracedIndex[std::size_t(k)] < 0) {
            if (hooks.warnings)
                hooks.warnings->push_back(
                    "parameter sample " + std::to_string(k) +
                    " (t = " + std::to_string(fit.parameter) +
                    "): the camera sees no reflector pixel there; the sample is left out and the "
                    "runtime blends its neighbours across it");
            fit.leftOut = true;
            fit.psnrOn = std::numeric_limits<double>::quiet_NaN();
            if (hooks.fits) hooks.fits->push_back(fit);
            continue;
        }
        const PemSamples& samples = traced[std::size_t(tracedIndex[std::size_t(k)])];
        PemSampleMap m = bake.infer(k, samples, decision, &fit);
        if (hooks.fits) {
            fit.parameter = m.parameter;
            fit.localLayer = decision.local;
            fit.rays = int(samples.size());
            fit.selfHitFraction = pemCoverage(samples).fraction();
            fit.psnrOn = pemSamplesPsnr(
                samples, [&](const PemSample& p) { return sampleRadiance(m, decision.local, p); },
                pemRows(s));
            hooks.fits->push_back(fit);
        }
        maps.push_back(std::move(m));
        if (hooks.progress) hooks.progress(share * (0.5 + 0.5 * double(k + 1) / double(s.samples)));
    }
    traced.clear();
    PemAsset asset = bake.assemble(decision, std::move(maps));
    if (hooks.fits)
        measureOffManifold(asset, s, hooks, scene.path, [&](float t) { return bake.traceAt(t); });
    return asset;
}

} // namespace specula
