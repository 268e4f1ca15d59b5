#include "ggx_albedo_texture.h"

#include "engine/image/ggx_albedo.h"

namespace specula::gpu {

TextureSpec ggxAlbedoTextureSpec() {
    return {"uGgxAlbedo", GL_TEXTURE_2D, GL_R32F, kGgxAlbedoTableSize, kGgxAlbedoTableSize};
}

Texture createGgxAlbedoTexture(const TextureAllocator& allocate) {
    Texture texture = allocate(ggxAlbedoTextureSpec());
    const GLuint tex = texture.id();
    glTextureSubImage2D(tex, 0, 0, 0, kGgxAlbedoTableSize, kGgxAlbedoTableSize, GL_RED, GL_FLOAT,
                        ggxAlbedoTable().data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

} // namespace specula::gpu
