#pragma once
// An offscreen framebuffer: RGBA32F colour (linear radiance, no clamping) and a 32-bit
// float depth texture, both sampleable by later passes.
#include "engine/gpu/gl_objects.h"
#include "engine/image/image.h"

#include <glm/vec4.hpp>

namespace specula::gpu {

class RenderTarget {
public:
    RenderTarget() = default;
    RenderTarget(int width, int height); // needs a current context; throws on bad size

    int width() const { return width_; }
    int height() const { return height_; }
    glm::ivec2 size() const { return {width_, height_}; }

    // Binds the framebuffer for drawing and sets the viewport to the whole target.
    void bind() const;
    void clear(const glm::vec4& colour = glm::vec4(0.f), float depth = 1.f) const;

    // The colour as RGBA float with row 0 at the TOP (GL stores row 0 at the bottom).
    Image readback() const;
    // The depth buffer (window-space depth in [0, 1]), one channel, row 0 at the top.
    Image readbackDepth() const;

    const Framebuffer& framebuffer() const { return fbo_; }
    const Texture& colorTexture() const { return colour_; }
    const Texture& depthTexture() const { return depth_; }

private:
    int width_ = 0, height_ = 0;
    Texture colour_, depth_;
    Framebuffer fbo_;
};

} // namespace specula::gpu
