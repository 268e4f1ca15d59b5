#pragma once
// Owns the GPU side of every ReflectionProbe: cooked asset, texture array, sky, parameter
// block, and one shader permutation per distinct feature mask. Components stay plain
// structs: sync() sees a new or edited component (compared with the copy it last built
// from); a new asset rebuilds the textures, a parameter edit rewrites the block only.
#include "components/reflection_probe/distance_lookup_config.h"
#include "components/reflection_probe/lightfield_asset.h"
#include "components/reflection_probe/reflection_probe.h"
#include "engine/ecs/registry.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/render_target.h"
#include "engine/gpu/timer.h"
#include "engine/math/camera.h"
#include "engine/render/scene_renderer.h"

#include <array>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace specula {

struct ProbeFrameStats {
    double reflectorPassMs = 0.0; // GPU time of the last render() (timer query)
    std::size_t reflectorsDrawn = 0;
    std::size_t probeGpuBytes = 0;         // texture memory of all probes
    std::vector<std::string> permutations; // the compiled feature sets, e.g. "bisection"
    // Light-field probes are exact only for reflectors inside their cell: reflectors whose
    // world bounds reach outside it in the last render() (each is also logged once).
    std::size_t reflectorsOutsideCell = 0;
    bool reflectorLeftCell = false;
    bool lightFieldBackgroundDrawn = false; // the light field drew the environment this frame
    // Since the system was made (sync() adds, render() never resets): texture sets uploaded
    // (a probe's cube layers and sky, or its light-field atlas) and parameter blocks
    // uploaded. A new asset uploads textures; an edit of d_e, D or a method within the
    // flavour uploads the block only (or, to grow from the composite to every layer, both).
    std::size_t textureUploads = 0;
    std::size_t parameterUploads = 0;
};

class ReflectionProbeSystem {
public:
    ReflectionProbeSystem(); // needs a current GL 4.5 context
    ~ReflectionProbeSystem();

    // Creates, rebuilds or drops GPU state to match the ReflectionProbe components. Throws
    // Error naming the manifest when an asset is missing or invalid.
    void sync(ecs::Registry& registry);

    // Draws every Reflector into `target` (bound, depth already holding the environment
    // drawn by `scene`), timing the pass. `output` 1/2 write the twin's inputs instead of
    // colour: probe-local position / reflected direction.
    void render(ecs::Registry& registry, const CameraView& camera, SceneRenderer& scene,
                gpu::RenderTarget& target, int output = 0);

    const ProbeFrameStats& stats() const { return stats_; }
    // The CPU-side asset and lookup configuration of a synced probe (null if none).
    const DistanceProbeAsset* asset(ecs::Entity probe) const;
    const DistanceLookupConfig* config(ecs::Entity probe) const;
    // Light-field probes: the cooked asset (null if none) and the disparities the shader
    // uses now (the component's `disparity` when set, else the cooked per-slab values).
    const LightFieldAsset* lightFieldAsset(ecs::Entity probe) const;
    std::array<float, 6> lightFieldDisparities(ecs::Entity probe) const;

private:
    struct ProbeGpu;
    gpu::Program& program(std::uint32_t features, int output);
    void setDistanceParams(ProbeGpu& gpuProbe, const ReflectionProbe& probe);
    void syncLightField(ProbeGpu& gpuProbe);
    void bindLightField(gpu::Program& prog, const ProbeGpu& p);
    void drawLightFieldBackground(const ProbeGpu& p, const CameraView& camera, int output);
    void checkCell(ecs::Registry& registry, ecs::Entity reflector, const ProbeGpu& p);

    std::unordered_map<ecs::Entity, std::unique_ptr<ProbeGpu>> probes_;
    std::map<std::uint64_t, gpu::Program> programs_; // key: features | output << 32
    std::unordered_map<std::string, std::weak_ptr<const DistanceProbeAsset>> assetCache_;
    std::unordered_map<std::string, std::weak_ptr<const LightFieldAsset>> lightFieldCache_;
    std::unordered_set<ecs::Entity> warnedOutside_; // reflectors already logged as outside
    gpu::VertexArray emptyVao_;                     // the background pass draws no attributes
    std::unique_ptr<gpu::GpuTimer> timer_;
    ProbeFrameStats stats_;
};

// Permutation bits of the light-field flavour, apart from the distance bits so a cache key
// never confuses the two.
inline constexpr std::uint32_t kFeatureLightField = 1u << 16;
inline constexpr std::uint32_t kFeatureLightFieldBackground = 1u << 17;

// Human-readable name of a feature mask, e.g. "layers+bisection+avgdist+fresnel".
std::string featureName(std::uint32_t features);

} // namespace specula
