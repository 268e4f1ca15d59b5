#include "distance_textures.h"

#include <algorithm>
#include <vector>

namespace specula {

gpu::Texture createCubeArray(int faceRes, int cubes) {
    gpu::Texture array = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint tex = array.id();
    glTextureStorage3D(tex, 1, GL_RGBA32F, faceRes, faceRes, 6 * cubes);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return array;
}

void uploadCube(const gpu::Texture& array, int cube, const DistanceProbeLayer& layer) {
    for (int f = 0; f < 6; ++f) {
        const Image& face = layer.faces[std::size_t(f)];
        glTextureSubImage3D(array.id(), 0, 0, 0, 6 * cube + f, face.width, face.height, 1, GL_RGBA,
                            GL_FLOAT, face.pixels.data());
    }
}

std::size_t cubeArrayBytes(int faceRes, int cubes) {
    return std::size_t(faceRes) * std::size_t(faceRes) * 6 * std::size_t(cubes) * 16;
}

gpu::Texture uploadSkyTexture(const Image& sky) {
    gpu::Texture texture = gpu::Texture::create(GL_TEXTURE_2D);
    const GLuint s = texture.id();
    std::vector<float> rgba(std::size_t(sky.width) * sky.height * 4);
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            const glm::vec4 v = sky.rgba(x, y);
            std::copy(&v[0], &v[0] + 4, &rgba[(std::size_t(y) * sky.width + x) * 4]);
        }
    glTextureStorage2D(s, 1, GL_RGBA32F, sky.width, sky.height);
    glTextureSubImage2D(s, 0, 0, 0, sky.width, sky.height, GL_RGBA, GL_FLOAT, rgba.data());
    glTextureParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

std::size_t skyTextureBytes(const Image& sky) {
    return std::size_t(sky.width) * std::size_t(sky.height) * 4 * sizeof(float);
}

} // namespace specula
