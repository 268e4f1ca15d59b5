#pragma once
// A parameterized-environment-map probe for a host engine with its own renderer, entities and
// shaders, as DistanceHostProbe is for a distance probe (distance_host_probe.h):
//
//   specula::PemHostResult made = specula::PemHostProbe::create("pem/manifest.json");
//   if (!made) log(made.error);                        // an error value, never an abort
//   std::string fs = "#version 450 core\n" + made.probe->glslLibrary() + myFragmentShader;
//   ... each frame: made.probe->setSettings({.parameter = t}); // where on the cooked path
//   ... per draw, with the program in use: made.probe->bindTo(program);
//
// where myFragmentShader calls the same
//   vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// (shaders/pem_host.glsl). The parameter is the asset's (the viewpoint or the reflector along
// its cooked path, in [0, 1]). An asset's local layer needs the reflector's hull per triangle
// (Specula's own store draws it); the host library draws the distant layer. Specula's own
// PemStore binds the same PemGpuProbe. Managed or unmanaged (host_probe.h); destroy the probe
// while the context is current.
#include "components/reflection_probe/host_probe.h"
#include "components/reflection_probe/pem/pem_gpu_probe.h"

#include <string>

namespace specula {

struct PemHostOptions {
    PemProbe settings{};    // the first frame's parameter and blend
    PemBindings bindings{};       // texture units and the uniform-buffer binding
    UnmanagedObjects unmanaged{}; // the host's objects (describe()); empty: managed
};

class PemHostProbe;
using PemHostResult = HostResult<PemHostProbe>;

class PemHostProbe {
public:
    // Reads the cooked PEM probe at manifestPath and uploads its maps. Needs a current OpenGL
    // 4.5 core context.
    static PemHostResult create(const std::string& manifestPath,
                                const PemHostOptions& options = {});
    // The textures and buffer create() allocates for this asset (host_probe.h's unmanaged
    // mode; no GL needed).
    static HostLayout describe(const std::string& manifestPath);
    ~PemHostProbe();
    PemHostProbe(const PemHostProbe&) = delete;
    PemHostProbe& operator=(const PemHostProbe&) = delete;

    // GLSL (no #version) declaring speculaReflect and what it reads, compiled for this asset's
    // geometry (box or distance) and MIP levels.
    const std::string& glslLibrary() const { return library_; }
    // The parameter (and blend) of the frames to come: rewrites the parameter block only.
    void setSettings(const PemProbe& settings);
    // Binds the maps and the parameter block on the chosen units and binding point and points
    // `program`'s samplers and block at them. Call before drawing with the program.
    void bindTo(GLuint program) const;

    const PemAsset& asset() const { return *gpu_.asset; }
    const PemGpuProbe& gpu() const { return gpu_; }
    std::size_t gpuBytes() const { return gpu_.gpuBytes(); }

private:
    PemHostProbe() = default;
    PemHostOptions options_;
    PemGpuProbe gpu_;
    std::string library_;
};

} // namespace specula
