#pragma once
// A distance probe for a host engine that has its own renderer, entities and shaders (the
// shape of the SDKs engines adopt: the host owns the context and the frame, the SDK gets
// resources and ships its shader code as text the host's shaders call). In a few lines:
//
//   specula::DistanceHostResult made = specula::DistanceHostProbe::create("probe/manifest.json");
//   if (!made) log(made.error);                        // an error value, never an abort
//   std::string fs = "#version 450 core\n" + made.probe->glslLibrary() + myFragmentShader;
//   ... compile and link fs as usual; per draw, with the program in use:
//   made.probe->bindTo(program);                       // textures and block on chosen units
//
// where myFragmentShader calls
//   vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// (shaders/distance_host.glsl). Specula's own store binds the same DistanceGpuProbe. Managed
// or unmanaged (host_probe.h: describe(), then the host's objects in options.unmanaged).
// Destroy the probe while the context is current.
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/host_probe.h"

#include <memory>
#include <string>
#include <vector>

namespace specula {

struct DistanceHostOptions {
    // By default Planned: the methods and d_e the cooker's effect plan chose for this probe.
    DistanceProbe settings{};
    // Compile in and upload the GGX chain for rough reflectors (roughness > 0); without it
    // speculaReflect is a mirror at any roughness.
    bool glossy = false;
    // Texture units and the uniform-buffer binding the host leaves to Specula.
    DistanceBindings bindings{};
    UnmanagedObjects unmanaged{}; // the host's objects (describe()); empty: managed
};

class DistanceHostProbe;

using DistanceHostResult = HostResult<DistanceHostProbe>;

class DistanceHostProbe {
public:
    // Reads the cooked probe at manifestPath and uploads what its lookup reads. Needs a current
    // OpenGL 4.5 core context.
    static DistanceHostResult create(const std::string& manifestPath,
                                     const DistanceHostOptions& options = {});
    // The textures and buffer create() allocates for this asset and these options (no GL
    // needed): what the host makes in the unmanaged mode.
    static HostLayout describe(const std::string& manifestPath,
                               const DistanceHostOptions& options = {});
    ~DistanceHostProbe();
    DistanceHostProbe(const DistanceHostProbe&) = delete;
    DistanceHostProbe& operator=(const DistanceHostProbe&) = delete;

    // GLSL (no #version) declaring speculaReflect and what it reads, compiled for this
    // probe's methods and features only.
    const std::string& glslLibrary() const { return library_; }
    // Binds the probe's textures and parameter block on the chosen units and points
    // `program`'s samplers and block at them. Call before drawing with the program.
    void bindTo(GLuint program) const;

    glm::vec3 centre() const { return gpu_.config.params.centre; }
    const DistanceProbeAsset& asset() const { return *gpu_.asset; }
    const DistanceLookupConfig& config() const { return gpu_.config; }
    const DistanceGpuProbe& gpu() const { return gpu_; }
    std::size_t gpuBytes() const { return gpu_.gpuBytes(); }

private:
    DistanceHostProbe() = default;
    DistanceHostOptions options_;
    DistanceGpuProbe gpu_;
    gpu::Texture ggxAlbedo_;
    std::string library_;
};

} // namespace specula
