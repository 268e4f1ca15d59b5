#pragma once
// A light-field-slab probe for a host engine with its own renderer, entities and shaders, as
// DistanceHostProbe is for a distance probe (distance_host_probe.h):
//
//   specula::LightFieldHostResult made = specula::LightFieldHostProbe::create("lf/manifest.json");
//   if (!made) log(made.error);                        // an error value, never an abort
//   std::string fs = "#version 450 core\n" + made.probe->glslLibrary() + myFragmentShader;
//   ... per draw, with the program in use: made.probe->bindTo(program);
//
// where myFragmentShader calls the same
//   vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// (shaders/lightfield_host.glsl). The light field is exact for reflector points inside its
// cell (cellCentre() +- halfCell()). Specula's own LightFieldStore binds the same
// LightFieldGpuProbe. Managed or unmanaged (host_probe.h); destroy the probe while the context
// is current.
#include "components/reflection_probe/host_probe.h"
#include "components/reflection_probe/lightfield/lightfield_gpu_probe.h"

#include <string>

namespace specula {

struct LightFieldHostOptions {
    LightFieldProbe settings{}; // the disparity override (the cooked ones by default)
    // Compile in the GGX filter of the slabs and upload the atlas's mips for rough reflectors;
    // without it speculaReflect is a mirror at any roughness.
    bool glossy = false;
    LightFieldBindings bindings{}; // texture units the host leaves to Specula
    UnmanagedObjects unmanaged{};  // the host's textures (describe()); empty: managed
};

class LightFieldHostProbe;
using LightFieldHostResult = HostResult<LightFieldHostProbe>;

class LightFieldHostProbe {
public:
    // Reads the cooked light field at manifestPath and uploads its atlas. Needs a current
    // OpenGL 4.5 core context.
    static LightFieldHostResult create(const std::string& manifestPath,
                                       const LightFieldHostOptions& options = {});
    // The textures create() allocates for this asset and these options (host_probe.h's
    // unmanaged mode; no GL needed). A light field has no uniform buffer.
    static HostLayout describe(const std::string& manifestPath,
                               const LightFieldHostOptions& options = {});
    ~LightFieldHostProbe();
    LightFieldHostProbe(const LightFieldHostProbe&) = delete;
    LightFieldHostProbe& operator=(const LightFieldHostProbe&) = delete;

    // GLSL (no #version) declaring speculaReflect and what it reads.
    const std::string& glslLibrary() const { return library_; }
    // Binds the atlas (and the GGX albedo table) on the chosen units and sets `program`'s
    // lookup uniforms. Call before drawing with the program.
    void bindTo(GLuint program) const;

    glm::vec3 cellCentre() const { return gpu_.asset->cellCentre; }
    float halfCell() const { return gpu_.asset->halfCell(); }
    const LightFieldAsset& asset() const { return *gpu_.asset; }
    const LightFieldGpuProbe& gpu() const { return gpu_; }
    std::size_t gpuBytes() const { return gpu_.gpuBytes(); }

private:
    LightFieldHostProbe() = default;
    LightFieldHostOptions options_;
    LightFieldGpuProbe gpu_;
    gpu::Texture ggxAlbedo_;
    std::string library_;
};

} // namespace specula
