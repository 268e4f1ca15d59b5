#pragma once
// What a texture is, apart from its contents: the one description the runtime allocates
// from (managed) and a host allocates from before handing its texture over (unmanaged, the
// two ownership modes RTXGI offers). Immutable storage (glTextureStorage*), as the runtime's
// own textures have.
#include "engine/gpu/gl_objects.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace specula::gpu {

struct TextureSpec {
    std::string name;                    // what reads it: the sampler uniform of the runtime's GLSL
    GLenum target = GL_TEXTURE_2D_ARRAY; // GL_TEXTURE_2D or GL_TEXTURE_2D_ARRAY
    GLenum internalFormat = GL_RGBA32F;
    int width = 0, height = 0;
    int layers = 1; // array layers (1 for GL_TEXTURE_2D)
    int levels = 1; // mip levels of the storage
    bool operator==(const TextureSpec&) const = default;
};

// The texture glTextureStorage2D/3D allocates for `spec`, contents undefined.
Texture createTexture(const TextureSpec& spec);
// Empty when texture `id` of the current context has `spec`'s target, immutable internal
// format, size, layers and levels, else what differs ("internal format is GL_RGBA16F (0x881a),
// GL_RGBA32F (0x8814) expected").
std::string textureMismatch(GLuint id, const TextureSpec& spec);
// Empty when buffer `id` holds at least `bytes` and glNamedBufferSubData may write it (mutable
// storage, or immutable with GL_DYNAMIC_STORAGE_BIT), else why not.
std::string uniformBufferMismatch(GLuint id, std::size_t bytes);
// GL's name of an internal format the runtime uses ("GL_RGBA32F"), else its hex value.
std::string internalFormatName(GLenum format);

// Where a probe's textures come from: createTexture, or a host's textures (HostTextures).
using TextureAllocator = std::function<Texture(const TextureSpec&)>;

// A texture a host made from a spec and hands over by the spec's name.
struct HostTexture {
    std::string name;
    GLuint id = 0;
};
// An allocator that returns the host's texture of each spec's name, borrowed (never deleted
// by the runtime), once textureMismatch accepts it. Throws Error naming "textures.<name>" (in
// `file`) when the host handed none of that name or one that does not fit.
TextureAllocator hostTextureAllocator(std::vector<HostTexture> textures, std::string file);

} // namespace specula::gpu
