#include "bc1.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace specula {

namespace {

std::uint16_t pack565(glm::vec3 c) {
    const int r = std::clamp(int(std::lround(c.r * 31.f / 255.f)), 0, 31);
    const int g = std::clamp(int(std::lround(c.g * 63.f / 255.f)), 0, 63);
    const int b = std::clamp(int(std::lround(c.b * 31.f / 255.f)), 0, 31);
    return std::uint16_t((r << 11) | (g << 5) | b);
}

glm::ivec3 unpack565(std::uint16_t v) {
    const int r = (v >> 11) & 31, g = (v >> 5) & 63, b = v & 31;
    return {(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)};
}

std::uint16_t endpoint(const std::uint8_t* block, int k) {
    return std::uint16_t(block[2 * k] | (block[2 * k + 1] << 8));
}

// The palette of a block: four colours when c0 > c1 (the only mode the encoder writes),
// else three and transparent black.
void palette(std::uint16_t c0, std::uint16_t c1, glm::ivec3 out[4]) {
    out[0] = unpack565(c0);
    out[1] = unpack565(c1);
    if (c0 > c1) {
        out[2] = (2 * out[0] + out[1]) / 3;
        out[3] = (out[0] + 2 * out[1]) / 3;
    } else {
        out[2] = (out[0] + out[1]) / 2;
        out[3] = glm::ivec3(0);
    }
}

// The colours' principal axis: a few power iterations on their covariance about `mean`.
glm::vec3 principalAxis(const glm::vec3 px[16], glm::vec3 mean) {
    float cov[6] = {};
    for (int i = 0; i < 16; ++i) {
        const glm::vec3 d = px[i] - mean;
        cov[0] += d.r * d.r, cov[1] += d.r * d.g, cov[2] += d.r * d.b;
        cov[3] += d.g * d.g, cov[4] += d.g * d.b, cov[5] += d.b * d.b;
    }
    glm::vec3 axis(0.57735f);
    for (int it = 0; it < 6; ++it) {
        const glm::vec3 next(cov[0] * axis.r + cov[1] * axis.g + cov[2] * axis.b,
                             cov[1] * axis.r + cov[3] * axis.g + cov[4] * axis.b,
                             cov[2] * axis.r + cov[4] * axis.g + cov[5] * axis.b);
        const float len = glm::length(next);
        if (!(len > 1e-12f)) break;
        axis = next / len;
    }
    return axis;
}

// Each texel's nearest palette entry, 2 bits per texel.
std::uint32_t nearestIndices(const glm::vec3 px[16], std::uint16_t c0, std::uint16_t c1) {
    glm::ivec3 pal[4];
    palette(c0, c1, pal);
    std::uint32_t indices = 0;
    for (int i = 0; i < 16; ++i) {
        int best = 0;
        float bestD = std::numeric_limits<float>::max();
        for (int k = 0; k < 4; ++k) {
            const glm::vec3 d = px[i] - glm::vec3(pal[k]);
            const float dd = glm::dot(d, d);
            if (dd < bestD) bestD = dd, best = k;
        }
        indices |= std::uint32_t(best) << (2 * i);
    }
    return indices;
}

// One block: endpoints at the extremes of the colours along their principal axis, then each
// texel takes the nearest palette entry.
void encodeBlock(const glm::vec3 px[16], std::uint8_t out[8]) {
    glm::vec3 mean(0.f);
    for (int i = 0; i < 16; ++i)
        mean += px[i];
    mean /= 16.f;
    const glm::vec3 axis = principalAxis(px, mean);
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int i = 0; i < 16; ++i) {
        const float t = glm::dot(px[i] - mean, axis);
        lo = std::min(lo, t);
        hi = std::max(hi, t);
    }
    std::uint16_t c0 = pack565(glm::clamp(mean + hi * axis, 0.f, 255.f));
    std::uint16_t c1 = pack565(glm::clamp(mean + lo * axis, 0.f, 255.f));
    if (c0 < c1) std::swap(c0, c1);
    // c0 == c1: every index 0 (c0); the block is a single colour.
    const std::uint32_t indices = c0 != c1 ? nearestIndices(px, c0, c1) : 0;
    out[0] = std::uint8_t(c0 & 0xff), out[1] = std::uint8_t(c0 >> 8);
    out[2] = std::uint8_t(c1 & 0xff), out[3] = std::uint8_t(c1 >> 8);
    for (int k = 0; k < 4; ++k)
        out[4 + k] = std::uint8_t(indices >> (8 * k));
}

} // namespace

std::vector<std::uint8_t> encodeBC1(const std::uint8_t* rgb, int width, int height) {
    const int bw = width / 4, bh = height / 4;
    std::vector<std::uint8_t> out(std::size_t(bw) * bh * 8);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            glm::vec3 px[16];
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x) {
                    const std::uint8_t* p =
                        rgb + (std::size_t(by * 4 + y) * width + std::size_t(bx * 4 + x)) * 3;
                    px[y * 4 + x] = glm::vec3(p[0], p[1], p[2]);
                }
            encodeBlock(px, &out[(std::size_t(by) * bw + bx) * 8]);
        }
    return out;
}

std::vector<std::uint8_t> decodeBC1(const std::uint8_t* blocks, int width, int height) {
    const int bw = width / 4, bh = height / 4;
    std::vector<std::uint8_t> out(std::size_t(width) * height * 3);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const std::uint8_t* b = blocks + (std::size_t(by) * bw + bx) * 8;
            glm::ivec3 pal[4];
            palette(endpoint(b, 0), endpoint(b, 1), pal);
            const std::uint32_t idx = std::uint32_t(b[4]) | (std::uint32_t(b[5]) << 8) |
                                      (std::uint32_t(b[6]) << 16) | (std::uint32_t(b[7]) << 24);
            for (int i = 0; i < 16; ++i) {
                const glm::ivec3 c = pal[(idx >> (2 * i)) & 3];
                std::uint8_t* p =
                    &out[(std::size_t(by * 4 + i / 4) * width + std::size_t(bx * 4 + i % 4)) * 3];
                p[0] = std::uint8_t(c.r), p[1] = std::uint8_t(c.g), p[2] = std::uint8_t(c.b);
            }
        }
    return out;
}

std::optional<std::size_t> firstUndecodableBC1Block(std::span<const std::uint8_t> blocks) {
    for (std::size_t b = 0; b + 8 <= blocks.size(); b += 8) {
        const std::uint8_t* p = &blocks[b];
        if (endpoint(p, 0) > endpoint(p, 1)) continue;
        for (int i = 0; i < 16; ++i)
            if (((p[4 + i / 4] >> (2 * (i % 4))) & 3) == 3) return b / 8;
    }
    return std::nullopt;
}

} // namespace specula
