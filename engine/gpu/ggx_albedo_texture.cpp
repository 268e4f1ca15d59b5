#include "ggx_albedo_texture.h"

#include "engine/image/ggx_albedo.h"

namespace specula::gpu {

Texture createGgxAlbedoTexture() {
    Texture texture = Texture::create(GL_TEXTURE_2D);
    const GLuint tex = texture.id();
    glTextureStorage2D(tex, 1, GL_R32F, kGgxAlbedoTableSize, kGgxAlbedoTableSize);
    glTextureSubImage2D(tex, 0, 0, 0, kGgxAlbedoTableSize, kGgxAlbedoTableSize, GL_RED, GL_FLOAT,
                        ggxAlbedoTable().data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

} // namespace specula::gpu
