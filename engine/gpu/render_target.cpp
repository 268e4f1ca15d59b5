#include "engine/gpu/render_target.h"

#include "engine/core/error.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace specula::gpu {

RenderTarget::RenderTarget(int width, int height) : width_(width), height_(height) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (width <= 0 || height <= 0 || width > maxSize || height > maxSize)
        throw Error("RenderTarget", "size",
                    "expected 1.." + std::to_string(maxSize) + " per side, got " +
                        std::to_string(width) + "x" + std::to_string(height));
    colour_ = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(colour_.id(), 1, GL_RGBA32F, width, height);
    depth_ = Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
    for (GLuint t : {colour_.id(), depth_.id()}) {
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    }
    fbo_ = Framebuffer::create();
    glNamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, colour_.id(), 0);
    glNamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
    glNamedFramebufferDrawBuffer(fbo_.id(), GL_COLOR_ATTACHMENT0);
    const GLenum status = glCheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        throw Error("RenderTarget", "framebuffer",
                    "RGBA32F + DEPTH32F framebuffer incomplete (status " + std::to_string(status) +
                        ")");
}

void RenderTarget::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
    glViewport(0, 0, width_, height_);
}

void RenderTarget::clear(const glm::vec4& colour, float depth) const {
    glClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, &colour[0]);
    glClearNamedFramebufferfv(fbo_.id(), GL_DEPTH, 0, &depth);
}

namespace {
Image readTexture(const Texture& tex, int width, int height, int channels, GLenum format) {
    Image img(width, height, channels);
    const std::size_t rowFloats = std::size_t(width) * channels;
    std::vector<float> raw(rowFloats * height);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex.id(), 0, format, GL_FLOAT, GLsizei(raw.size() * sizeof(float)),
                      raw.data());
    // GL's first row is the bottom of the picture; Image's row 0 is the top.
    for (int y = 0; y < height; ++y)
        std::memcpy(img.at(0, y), raw.data() + rowFloats * std::size_t(height - 1 - y),
                    rowFloats * sizeof(float));
    return img;
}
} // namespace

Image RenderTarget::readback() const {
    return readTexture(colour_, width_, height_, 4, GL_RGBA);
}

Image RenderTarget::readbackDepth() const {
    return readTexture(depth_, width_, height_, 1, GL_DEPTH_COMPONENT);
}

} // namespace specula::gpu
