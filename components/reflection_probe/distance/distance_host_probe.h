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
// (shaders/distance_host.glsl). Specula's own store binds the same DistanceGpuProbe.
//
// Two ownership modes, as RTXGI offers: managed (the default), the probe creates and deletes
// its GL textures and buffer; unmanaged, the host asks describe() what the probe reads,
// creates those textures (glTextureStorage*, one per spec) and a uniform buffer itself, and
// hands them over in the options: the probe uploads into them, sets their sampling state and
// never deletes them. Destroy the probe while the context is current.
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
    // Unmanaged mode: the host's textures, one per spec describe() lists, by its name, and its
    // uniform buffer of describe().paramsBytes (GL_DYNAMIC_STORAGE_BIT). Empty / 0: the probe
    // creates its own.
    std::vector<gpu::HostTexture> textures{};
    GLuint paramsBuffer = 0;
};

// What a probe of an asset reads, for a host that creates the GL objects itself.
struct DistanceHostLayout {
    std::vector<gpu::TextureSpec> textures; // by the sampler uniform that reads each
    std::size_t paramsBytes = 0;            // the parameter block's uniform buffer
    std::string error;                      // names the asset and field; empty when described
    explicit operator bool() const { return error.empty(); }
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
    static DistanceHostLayout describe(const std::string& manifestPath,
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
