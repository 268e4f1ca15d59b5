#include "reflection_probe_system.h"

#include "components/reflection_probe/asset_format.h"
#include "components/reflection_probe/distance/system/distance_level_store.h"
#include "components/reflection_probe/distance/system/distance_store.h"
#include "components/reflection_probe/level_index.h"
#include "components/reflection_probe/lightfield/system/lightfield_store.h"
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/pem/system/pem_store.h"
#include "engine/core/error.h"

#include <algorithm>

namespace specula {

void ProbeFrameStats::drew(const std::string& variantName) {
    if (std::find(permutations.begin(), permutations.end(), variantName) == permutations.end())
        permutations.push_back(variantName);
}

ReflectionProbeSystem::ReflectionProbeSystem() : timer_(std::make_unique<gpu::GpuTimer>()) {
    addFlavour(std::make_unique<DistanceStore>());
    addFlavour(std::make_unique<DistanceLevelStore>());
    addFlavour(std::make_unique<LightFieldStore>());
    addFlavour(std::make_unique<PemStore>());
}

ReflectionProbeSystem::~ReflectionProbeSystem() = default;

void ReflectionProbeSystem::addFlavour(std::unique_ptr<ProbeFlavourStore> store) {
    for (const auto& s : stores_)
        if (s->flavour() == store->flavour())
            throw Error("ReflectionProbeSystem", "flavour",
                        "flavour \"" + std::string(store->flavour()) + "\" is registered twice");
    stores_.push_back(std::move(store));
}

ProbeFlavourStore& ReflectionProbeSystem::storeFor(const ProbeManifest& manifest) const {
    // A level index (level_index.h) goes to its flavour's level store ("distance-level").
    const ManifestFields r{manifest.path};
    const bool level = assetFormatName(manifest.json) == std::string(kLevelFormat.name);
    if (level) readAssetFormat(manifest.json, kLevelFormat, manifest.path);
    const std::string flavour = level ? r.string(manifest.json, "flavour", "") + "-level"
                                      : r.probeFlavour(manifest.json);
    std::string known;
    for (const auto& s : stores_) {
        if (s->flavour() == flavour) return *s;
        known += (known.empty() ? "" : ", ") + std::string(s->flavour());
    }
    throw Error(manifest.path, "flavour",
                "no flavour \"" + flavour + "\" is registered (known: " + known + ")");
}

void ReflectionProbeSystem::load(ecs::Entity e, const ReflectionProbe& probe, Loaded& slot) {
    const ParsedManifest parsed = ParsedManifest::load(probe.asset);
    const ProbeManifest manifest = parsed.view();
    ProbeFlavourStore& store = storeFor(manifest);
    store.load(e, manifest, stats_); // throws before anything changed
    if (slot.store && slot.store != &store) slot.store->drop(e);
    slot = {probe.asset, &store};
}

void ReflectionProbeSystem::sync(ecs::Registry& registry) {
    // Drop probes whose entity or component is gone.
    std::erase_if(probes_, [&](const auto& kv) {
        if (registry.valid(kv.first) && registry.has<ReflectionProbe>(kv.first)) return false;
        kv.second.store->drop(kv.first);
        return true;
    });
    registry.view<ReflectionProbe>().each([&](ecs::Entity e, ReflectionProbe& probe) {
        Loaded& slot = probes_[e];
        if (!slot.store || slot.asset != probe.asset) {
            try {
                load(e, probe, slot);
            } catch (...) {
                if (!slot.store) probes_.erase(e);
                throw;
            }
        }
        for (const auto& s : stores_)
            if (s.get() != slot.store && s->holdsSettings(registry, e))
                throw Error(probe.asset, "flavour",
                            "the manifest's flavour is \"" + std::string(slot.store->flavour()) +
                                "\" but the probe entity holds " + std::string(s->settingsName()) +
                                " settings");
        slot.store->update(registry, e, stats_);
    });
    for (const auto& s : stores_)
        s->syncReflectors(registry, stats_);
    stats_.probeGpuBytes = 0;
    for (const auto& s : stores_)
        stats_.probeGpuBytes += s->gpuBytes();
}

void ReflectionProbeSystem::render(ecs::Registry& registry, const CameraView& camera,
                                   SceneRenderer& scene, gpu::RenderTarget& target, int output) {
    target.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    stats_.reflectorsDrawn = 0;
    stats_.permutations.clear();
    stats_.reflectorsOutsideCell = 0;
    stats_.reflectorLeftCell = false;
    stats_.backgroundDrawn = false;
    const ProbeDrawContext ctx{registry, camera, scene, output, stats_};
    // A background replaces the environment's colour (its depth stays, so reflectors are
    // still occluded by it) before the timed reflector pass.
    for (const auto& s : stores_)
        s->drawBackground(ctx);
    timer_->begin();
    registry.view<Reflector>().each([&](ecs::Entity e, Reflector& r) {
        auto it = probes_.find(r.probe);
        if (it == probes_.end() || !scene.contains(e)) return;
        if (it->second.store->drawReflector(ctx, e, r)) ++stats_.reflectorsDrawn;
    });
    timer_->end();
    stats_.reflectorPassMs = timer_->resultMs();
}

} // namespace specula
