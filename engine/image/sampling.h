#pragma once
// CPU texture sampling that matches OpenGL's GL_LINEAR / GL_NEAREST without mipmaps:
// texel centres at (i + 0.5) / size, (u, v) = (0, 0) at the first stored row. The CPU twins
// of the shaders and the ray tracer sample through these so they read what the GPU reads.
#include "engine/image/image.h"

#include <cmath>

#include <glm/common.hpp>

namespace specula {

enum class Wrap { Repeat, Clamp };

inline int wrapIndex(int i, int size, Wrap wrap) {
    if (wrap == Wrap::Clamp) return i < 0 ? 0 : (i >= size ? size - 1 : i);
    const int m = i % size;
    return m < 0 ? m + size : m;
}

inline glm::vec4 sampleNearest(const Image& img, glm::vec2 uv, Wrap wrap) {
    const int x = wrapIndex(int(std::floor(uv.x * float(img.width))), img.width, wrap);
    const int y = wrapIndex(int(std::floor(uv.y * float(img.height))), img.height, wrap);
    return img.rgba(x, y);
}

// Separate wrap modes per axis, as for an equirectangular sky (S = repeat, T = clamp).
inline glm::vec4 sampleBilinear(const Image& img, glm::vec2 uv, Wrap wrapU, Wrap wrapV) {
    const float fx = uv.x * float(img.width) - 0.5f;
    const float fy = uv.y * float(img.height) - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const int xa = wrapIndex(x0, img.width, wrapU), xb = wrapIndex(x0 + 1, img.width, wrapU);
    const int ya = wrapIndex(y0, img.height, wrapV), yb = wrapIndex(y0 + 1, img.height, wrapV);
    const glm::vec4 top = glm::mix(img.rgba(xa, ya), img.rgba(xb, ya), ax);
    const glm::vec4 bottom = glm::mix(img.rgba(xa, yb), img.rgba(xb, yb), ax);
    return glm::mix(top, bottom, ay);
}

inline glm::vec4 sampleBilinear(const Image& img, glm::vec2 uv, Wrap wrap) {
    return sampleBilinear(img, uv, wrap, wrap);
}

} // namespace specula
