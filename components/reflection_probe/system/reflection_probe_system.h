#pragma once
// Owns the GPU side of every ReflectionProbe through one store per flavour. sync() reads a
// new or re-pointed probe's manifest once and hands it to the store its "flavour" names;
// every store then applies its settings component (an edit rewrites parameters only) and
// makes what the reflectors need (syncReflectors: a rough reflector's glossy chain).
// render() lets each store draw its background, then draws every Reflector through the store
// of its probe. Nothing here knows a flavour: each registers itself with addFlavour().
#include "components/reflection_probe/system/probe_flavour.h"
#include "components/reflection_probe/system/reflection_probe.h"
#include "engine/ecs/registry.h"
#include "engine/gpu/render_target.h"
#include "engine/gpu/timer.h"
#include "engine/math/camera.h"
#include "engine/render/scene_renderer.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace specula {

class ReflectionProbeSystem {
public:
    // Needs a current GL 4.5 context; registers the built-in flavours (distance, light field,
    // parameterized environment maps).
    ReflectionProbeSystem();
    ~ReflectionProbeSystem();

    // Registers a flavour: manifests whose "flavour" is store->flavour() load into it.
    void addFlavour(std::unique_ptr<ProbeFlavourStore> store);
    // The registered store of type S (null if none), for flavour-specific queries.
    template <typename S> S* store() const {
        for (const auto& s : stores_)
            if (auto* typed = dynamic_cast<S*>(s.get())) return typed;
        return nullptr;
    }

    // Creates, rebuilds or drops GPU state to match the ReflectionProbe components. Throws
    // Error naming the manifest when an asset is missing or invalid, its flavour is not
    // registered, or the entity holds another flavour's settings.
    void sync(ecs::Registry& registry);

    // Draws every Reflector into `target` (bound, depth already holding the environment
    // drawn by `scene`), timing the pass. `output` 1/2 write the twin's inputs instead of
    // colour: probe-local position / reflected direction.
    void render(ecs::Registry& registry, const CameraView& camera, SceneRenderer& scene,
                gpu::RenderTarget& target, int output = 0);

    const ProbeFrameStats& stats() const { return stats_; }

private:
    struct Loaded {
        std::string asset;
        ProbeFlavourStore* store = nullptr;
    };
    ProbeFlavourStore& storeFor(const ProbeManifest& manifest) const;
    void load(ecs::Entity e, const ReflectionProbe& probe, Loaded& slot);

    std::vector<std::unique_ptr<ProbeFlavourStore>> stores_;
    std::unordered_map<ecs::Entity, Loaded> probes_;
    std::unique_ptr<gpu::GpuTimer> timer_;
    ProbeFrameStats stats_;
};

} // namespace specula
