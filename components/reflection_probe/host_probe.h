#pragma once
// What every flavour's host API shares (distance/distance_host_probe.h and the level's): the
// answer of create() as a value, the GL checks made before any GL object, and the GLSL a
// host's shader prepends.
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/texture_spec.h"

#include <memory>
#include <string>
#include <vector>

namespace specula {

// create()'s answer: a probe, or an error that names the asset and field (or the GL feature)
// and leaves the host's GL state as it was.
template <typename Probe> struct HostResult {
    std::unique_ptr<Probe> probe;
    std::string error;
    explicit operator bool() const { return probe != nullptr; }
};

// Two ownership modes, as RTXGI offers: managed (the default), a host probe creates and
// deletes its GL textures and buffer; unmanaged, the host asks the probe's describe() what it
// reads, creates those objects itself (glTextureStorage*, one per spec; a uniform buffer of
// paramsBytes with GL_DYNAMIC_STORAGE_BIT) and hands them over in the options: the probe
// uploads into them, sets their sampling state and never deletes them.
struct HostLayout {
    std::vector<gpu::TextureSpec> textures; // by the sampler uniform that reads each
    std::size_t paramsBytes = 0;            // the parameter block's uniform buffer; 0: none
    std::string error;                      // names the asset and field; empty when described
    explicit operator bool() const { return error.empty(); }
};
// The unmanaged mode's objects in a host probe's options; empty: managed.
struct UnmanagedObjects {
    std::vector<gpu::HostTexture> textures{}; // one per described spec, by its name
    GLuint paramsBuffer = 0;
};
// Where a host probe's textures come from: the runtime's own when `objects` hands none, else
// the host's, every one checked against `layout` here, before anything is uploaded (and the
// buffer against its size). Throws Error naming `file` and "textures.<name>" or "paramsBuffer".
gpu::TextureAllocator hostAllocator(const UnmanagedObjects& objects, const HostLayout& layout,
                                    const std::string& file);

// Empty when the current context can run the lookups on textures of faceRes^2 and `layers`
// array layers, else why not: no current context, below OpenGL 4.5, a size over the limits.
std::string missingHostGlFeature(int faceRes, int layers);

// `shader` (a path the runtime embeds) expanded with `defines`, without its #version line:
// the host writes its own first.
std::string hostGlslLibrary(const std::string& shader, const std::vector<std::string>& defines);

// What every GPU probe's bindTo does to a program it does not own (a host's, or Specula's own):
// `texture` on `unit` and the sampler uniform `name` pointed at it; an int uniform; the uniform
// block `block` pointed at `binding`. Names the program does not use are skipped.
void bindSampler(GLuint program, const char* name, GLuint unit, GLuint texture);
void setIntUniform(GLuint program, const char* name, int value);
void bindUniformBlock(GLuint program, const char* block, GLuint binding);

// Throws Error(file) when the GL error flag is set after creating a host probe's objects.
void throwOnHostGlError(const std::string& file);

} // namespace specula
