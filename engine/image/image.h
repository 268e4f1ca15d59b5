#pragma once
// A linear-float RGBA-or-fewer image in row-major order, row 0 at the top.
#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

namespace specula {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;
    std::vector<float> pixels; // width * height * channels

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c) {}

    bool empty() const { return pixels.empty(); }
    float* at(int x, int y) { return &pixels[(std::size_t(y) * width + x) * channels]; }
    const float* at(int x, int y) const { return &pixels[(std::size_t(y) * width + x) * channels]; }
    // Reads up to four channels; missing ones read as 0 (alpha as 1).
    glm::vec4 rgba(int x, int y) const {
        const float* p = at(x, y);
        glm::vec4 v(0.f, 0.f, 0.f, 1.f);
        for (int c = 0; c < channels && c < 4; ++c)
            v[c] = p[c];
        return v;
    }
};

} // namespace specula
