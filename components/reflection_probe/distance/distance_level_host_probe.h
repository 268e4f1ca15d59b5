#pragma once
// A baked level of distance probes (DIR/level.json) for a host engine with its own renderer,
// entities and shaders: as DistanceHostProbe (distance_host_probe.h), with the level's blend.
// The host's shader prepends glslLibrary() and calls the same
//   vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// which blends up to settings.k probes per pixel (shaders/distance_level_host.glsl). Per draw,
// bindTo(program, reflectorBounds) hands over the probes whose influence meets the reflector's
// world bounds (probesFor): the per-reflector data, computed on the CPU, the pixels blend
// among them. Specula's own DistanceLevelStore binds the same DistanceLevelGpu.
#include "components/reflection_probe/distance/distance_level_gpu.h"
#include "components/reflection_probe/host_probe.h"

#include <string>
#include <vector>

namespace specula {

struct DistanceLevelHostOptions {
    DistanceLevel settings{}; // lookup method, blend and K
    // Compile in and upload every probe's GGX chain for rough reflectors; without it
    // speculaReflect is a mirror at any roughness.
    bool glossy = false;
    DistanceLevelBindings bindings{}; // texture units and the uniform-buffer binding
    UnmanagedObjects unmanaged{};     // the host's objects (describe()); empty: managed
};

class DistanceLevelHostProbe;
using DistanceLevelHostResult = HostResult<DistanceLevelHostProbe>;

class DistanceLevelHostProbe {
public:
    // Reads the level index and every probe it lists and uploads them. Needs a current OpenGL
    // 4.5 core context.
    static DistanceLevelHostResult create(const std::string& levelIndexPath,
                                          const DistanceLevelHostOptions& options = {});
    // The textures and buffer create() allocates for this level and these options
    // (host_probe.h's unmanaged mode; no GL needed).
    static HostLayout describe(const std::string& levelIndexPath,
                               const DistanceLevelHostOptions& options = {});
    ~DistanceLevelHostProbe();
    DistanceLevelHostProbe(const DistanceLevelHostProbe&) = delete;
    DistanceLevelHostProbe& operator=(const DistanceLevelHostProbe&) = delete;

    const std::string& glslLibrary() const { return library_; }
    // The probes a reflector within `bounds` (world space) blends among, in blend order
    // (indices into volumes()); empty bounds: every probe.
    std::vector<GLint> probesFor(const Aabb& bounds) const { return gpu_.candidatesFor(bounds); }
    // Binds the level's textures and block on the chosen units and hands `program` the
    // probes of a reflector within `reflectorBounds`. Call before drawing that reflector.
    void bindTo(GLuint program, const Aabb& reflectorBounds = {}) const;

    const std::vector<ProbeVolume>& volumes() const { return gpu_.volumes; }
    const DistanceLevelGpu& gpu() const { return gpu_; }
    std::size_t gpuBytes() const { return gpu_.gpuBytes(); }

private:
    DistanceLevelHostProbe() = default;
    DistanceLevelHostOptions options_;
    DistanceLevelGpu gpu_;
    gpu::Texture ggxAlbedo_;
    std::string library_;
};

} // namespace specula
