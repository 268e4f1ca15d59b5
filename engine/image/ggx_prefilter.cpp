#include "engine/image/ggx_prefilter.h"

#include "engine/image/ggx_lobe_filter.h"

#include "engine/core/error.h"
#include "engine/core/parallel_for.h"
#include "engine/math/cube_face.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <glm/geometric.hpp>

namespace specula {
namespace glsl {
namespace {
// sampleChain is the shared sampler (engine/math/cube_chain_sample.glsl.h) over the chain's
// images, so the shader that includes the same file samples exactly what the tests hold here.
struct ChainSampler {
    const CubeChain* chain;

    vec3 fetchChainTexel(int level, int face, ivec2 texel) const {
        return vec3(chain->levels[std::size_t(level)][std::size_t(face)].rgba(texel.x, texel.y));
    }
    int chainFaceRes(int level) const { return chain->levels[std::size_t(level)][0].width; }

#include "engine/math/cube_chain_sample.glsl.h"
};
} // namespace
} // namespace glsl

namespace {

int levelSize(int n, int level) {
    return std::max(1, n >> std::min(level, 30));
}

// Bilinear at (u, v) of `face`, taps past the edges read across them.
glm::vec4 bilinearAcross(const CubeFaces& faces, int face, float u, float v) {
    using ggx_filter::texelAcross;
    const int n = faces[face].width;
    const float fx = u * float(n) - 0.5f, fy = v * float(n) - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = int(x0f), y0 = int(y0f);
    const glm::vec4 top =
        glm::mix(texelAcross(faces, face, x0, y0), texelAcross(faces, face, x0 + 1, y0), ax);
    const glm::vec4 bottom = glm::mix(texelAcross(faces, face, x0, y0 + 1),
                                      texelAcross(faces, face, x0 + 1, y0 + 1), ax);
    return glm::mix(top, bottom, ay);
}

// A level of m x m faces of `channels` floats a texel, rows in parallel: texel(face, x, y, q)
// writes texel (x, y) of `face` into q.
template <typename Texel> CubeFaces computeLevel(int m, int channels, const Texel& texel) {
    CubeFaces out;
    for (Image& img : out)
        img = Image(m, m, channels);
    parallelForRanges(0, 6 * m, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const int face = row / m, y = row % m;
            for (int x = 0; x < m; ++x)
                texel(face, x, y, out[face].at(x, y));
        }
    });
    return out;
}

// Level-0 texels [lo, hi] that overlap texel x of a face of m texels over one of n texels.
void footprint(int x, int m, int n, int& lo, int& hi) {
    lo = int((std::int64_t(x) * n) / m);
    hi = int(((std::int64_t(x) + 1) * n + m - 1) / m) - 1;
}

// The solid angles of one n x n face's texels (the same on all six).
std::vector<double> solidAngleTable(int n) {
    std::vector<double> table(std::size_t(n) * n);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            table[std::size_t(y) * n + x] = cubeFaceTexelSolidAngle(n, x, y);
    return table;
}

// Box-filtered RGB mips of the input, each texel the solid-angle-weighted mean of the
// level-0 texels under it (by overlap, so any n works), down to 1 x 1.
std::vector<CubeFaces> radianceMips(const CubeFaces& faces, const std::vector<double>& omega) {
    const int n = faces[0].width;
    std::vector<CubeFaces> mips;
    mips.push_back(faces);
    for (int level = 1; levelSize(n, level - 1) > 1; ++level) {
        const int m = levelSize(n, level);
        mips.push_back(computeLevel(m, 3, [&](int face, int x, int y, float* q) {
            int y0, y1, x0, x1;
            footprint(y, m, n, y0, y1);
            footprint(x, m, n, x0, x1);
            double sum[3] = {0, 0, 0}, wsum = 0;
            for (int sy = y0; sy <= y1; ++sy) {
                // Overlap of source row sy with the coarse texel, in source texels.
                const double oy = std::min(double(sy + 1), double(y + 1) * n / m) -
                                  std::max(double(sy), double(y) * n / m);
                for (int sx = x0; sx <= x1; ++sx) {
                    const double ox = std::min(double(sx + 1), double(x + 1) * n / m) -
                                      std::max(double(sx), double(x) * n / m);
                    const double w = ox * oy * omega[std::size_t(sy) * n + sx];
                    const float* p = faces[face].at(sx, sy);
                    for (int c = 0; c < 3; ++c)
                        sum[c] += w * double(p[c]);
                    wsum += w;
                }
            }
            for (int c = 0; c < 3; ++c)
                q[c] = float(sum[c] / wsum);
        }));
    }
    return mips;
}

// Min and max of the finite level-0 distances under each texel of a level of m texels.
CubeFaces minMaxLevel(const CubeFaces& faces, int m, float dInf) {
    const int n = faces[0].width;
    return computeLevel(m, 2, [&](int face, int x, int y, float* q) {
        int y0, y1, x0, x1;
        footprint(y, m, n, y0, y1);
        footprint(x, m, n, x0, x1);
        float lo = dInf, hi = dInf;
        bool any = false;
        for (int sy = y0; sy <= y1; ++sy)
            for (int sx = x0; sx <= x1; ++sx) {
                const float d = faces[face].at(sx, sy)[3];
                if (!(d < dInf)) continue; // a miss, or NaN
                lo = any ? std::min(lo, d) : d;
                hi = any ? std::max(hi, d) : d;
                any = true;
            }
        q[0] = lo;
        q[1] = hi;
    });
}

void validate(const CubeFaces& faces, const GgxPrefilterOptions& options) {
    const int n = faces[0].width;
    for (int f = 0; f < 6; ++f) {
        const Image& img = faces[f];
        const std::string field = "face " + std::to_string(f);
        if (img.width < 1 || img.width != n || img.height != n)
            throw Error("", field,
                        "cube faces must be square and of one size (face 0 is " +
                            std::to_string(n) + " wide), got " + std::to_string(img.width) + "x" +
                            std::to_string(img.height));
        if (img.channels != 4 || img.pixels.size() != std::size_t(n) * n * 4)
            throw Error("", field,
                        "expected 4 channels (RGB radiance, A distance), got " +
                            std::to_string(img.channels));
    }
    if (options.levels < 1)
        throw Error("", "levels", "expected at least 1, got " + std::to_string(options.levels));
    if (options.samples < 1)
        throw Error("", "samples", "expected at least 1, got " + std::to_string(options.samples));
    if (!std::isfinite(options.lodBias)) throw Error("", "lodBias", "expected a finite number");
    if (!(options.dInf > 0.f)) throw Error("", "dInf", "expected a positive distance");
}

} // namespace

float ggxChainRoughness(int level, int levels) {
    return levels > 1 ? float(level) / float(levels - 1) : 0.f;
}

float ggxChainLevel(float roughness, int levels) {
    return std::clamp(roughness, 0.f, 1.f) * float(std::max(levels - 1, 0));
}

int ggxChainSamples(int level, const GgxPrefilterOptions& options) {
    if (level < 1) return 0;
    const std::int64_t s = std::int64_t(options.samples) << std::min(level - 1, 30);
    return int(std::min<std::int64_t>(s, std::max(options.samples, options.maxSamples)));
}

double cubeFaceTexelSolidAngle(int n, int x, int y) {
    // The solid angle of [-1, s] x [-1, t] on the face z = 1 up to constants: integral of
    // ds dt / (1 + s^2 + t^2)^1.5 has antiderivative atan(s t / sqrt(1 + s^2 + t^2)).
    const auto f = [](double s, double t) {
        return std::atan2(s * t, std::sqrt(1 + s * s + t * t));
    };
    const double s0 = 2.0 * x / n - 1.0, s1 = 2.0 * (x + 1) / n - 1.0;
    const double t0 = 2.0 * y / n - 1.0, t1 = 2.0 * (y + 1) / n - 1.0;
    return f(s1, t1) - f(s0, t1) - f(s1, t0) + f(s0, t0);
}

glm::vec4 sampleCubeBilinear(const CubeFaces& faces, glm::vec3 dir) {
    const glm::vec3 uvf = glsl::cubeFaceUv(dir);
    return bilinearAcross(faces, int(uvf.z), uvf.x, uvf.y);
}

CubeChain prefilterGgx(const CubeFaces& faces, const GgxPrefilterOptions& options) {
    validate(faces, options);
    const int n = faces[0].width;
    CubeChain chain;
    chain.dInf = options.dInf;
    chain.levels.push_back(faces);
    chain.roughness.push_back(0.f);
    chain.minMaxDistance.push_back(minMaxLevel(faces, n, options.dInf));
    if (options.levels == 1) return chain;

    std::vector<CubeFaces> radiance =
        ggx_filter::filterGgxLevels(radianceMips(faces, solidAngleTable(n)), options);
    for (int level = 1; level < options.levels; ++level) {
        const int m = levelSize(n, level);
        const float r = ggxChainRoughness(level, options.levels);
        CubeFaces& rgba = radiance[std::size_t(level - 1)];
        CubeFaces minMax = minMaxLevel(faces, m, options.dInf);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x)
                    rgba[f].at(x, y)[3] = minMax[f].at(x, y)[0];
        chain.levels.push_back(std::move(rgba));
        chain.roughness.push_back(r);
        chain.minMaxDistance.push_back(std::move(minMax));
    }
    return chain;
}

glm::vec3 sampleChain(const CubeChain& chain, glm::vec3 dir, float level) {
    glsl::ChainSampler sampler{&chain};
    return sampler.sampleCubeChain(dir, level, int(chain.levels.size()));
}

glm::vec2 fetchMinMaxDistance(const CubeChain& chain, glm::vec3 dir, int level) {
    const int l = std::clamp(level, 0, int(chain.minMaxDistance.size()) - 1);
    const glm::vec3 uvf = glsl::cubeFaceUv(dir);
    const Image& img = chain.minMaxDistance[l][int(uvf.z)];
    const int x = std::clamp(int(std::floor(uvf.x * float(img.width))), 0, img.width - 1);
    const int y = std::clamp(int(std::floor(uvf.y * float(img.height))), 0, img.height - 1);
    return glm::vec2(img.at(x, y)[0], img.at(x, y)[1]);
}

} // namespace specula
