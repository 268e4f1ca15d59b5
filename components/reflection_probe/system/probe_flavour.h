#pragma once
// What a probe flavour gives ReflectionProbeSystem: a store that owns the GPU state of every
// probe of that flavour. The system reads each probe's manifest once, lets the manifest's
// "flavour" pick the store, and runs the same load / update / draw on every store; it never
// switches on a flavour. A flavour is one folder (distance/, lightfield/, or one a test
// defines) holding its settings component, asset reader, shaders, CPU twin and store.
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/system/reflection_probe.h"
#include "engine/ecs/registry.h"
#include "engine/math/camera.h"
#include "engine/render/scene_renderer.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace specula {

struct ProbeFrameStats {
    double reflectorPassMs = 0.0; // GPU time of the last render() (timer query)
    std::size_t reflectorsDrawn = 0;
    std::size_t probeGpuBytes = 0;         // texture memory of all probes
    std::vector<std::string> permutations; // the compiled variants drawn, e.g. "bisection"
    // Flavours exact only inside a volume (the light-field cell): reflectors whose world
    // bounds reach outside it in the last render() (each is also logged once).
    std::size_t reflectorsOutsideCell = 0;
    bool reflectorLeftCell = false;
    bool backgroundDrawn = false; // a probe drew the environment this frame (light field)
    // Since the system was made (never reset): texture sets uploaded (a probe's textures
    // for a new asset, or grown for a method that reads more of it) and parameter blocks
    // uploaded (every settings edit; a new asset uploads one too).
    std::size_t textureUploads = 0;
    std::size_t parameterUploads = 0;

    // Records a variant's name in `permutations` once per frame.
    void drew(const std::string& variantName);
};

// What a store's draw calls need this frame.
struct ProbeDrawContext {
    ecs::Registry& registry;
    const CameraView& camera;
    SceneRenderer& scene;
    int output; // 0 colour, 1 probe-local position, 2 reflected direction (twin inputs)
    ProbeFrameStats& stats;
};

class ProbeFlavourStore {
public:
    virtual ~ProbeFlavourStore() = default;

    // The manifest "flavour" this store loads ("distance", "lightfield", ...).
    virtual std::string_view flavour() const = 0;
    // The name of the flavour's settings component, for messages ("DistanceProbe").
    virtual std::string_view settingsName() const = 0;

    // Loads the asset of `probe` from its parsed manifest and uploads it, replacing what the
    // store held for it. Throws Error naming the manifest and field; on a throw the store's
    // state for `probe` is unchanged.
    virtual void load(ecs::Entity probe, const ProbeManifest& manifest, ProbeFrameStats& stats) = 0;
    // Applies the flavour's settings component of a loaded probe (its defaults when the
    // entity has none). Cheap when nothing changed; an edit rewrites parameters only.
    virtual void update(const ecs::Registry& registry, ecs::Entity probe,
                        ProbeFrameStats& stats) = 0;
    virtual void drop(ecs::Entity probe) = 0;
    // After every probe's update: what this frame's reflectors need from the store's probes
    // beyond their settings (the distance flavour's glossy chain for rough reflectors), made
    // here so that the timed reflector pass only draws.
    virtual void syncReflectors(ecs::Registry&, ProbeFrameStats&) {}
    virtual bool holdsSettings(const ecs::Registry& registry, ecs::Entity probe) const = 0;
    virtual std::size_t gpuBytes() const = 0;

    // Before the timed reflector pass: what the flavour draws in place of the environment.
    virtual void drawBackground(const ProbeDrawContext&) {}
    // One reflector of a probe this store loaded; false when that probe cannot draw yet.
    virtual bool drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                               const Reflector& r) = 0;
};

} // namespace specula
