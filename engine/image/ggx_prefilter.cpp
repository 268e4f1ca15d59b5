#include "engine/image/ggx_prefilter.h"

#include "engine/core/error.h"
#include "engine/math/cube_face.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

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

constexpr double kPi = 3.14159265358979323846;

int levelSize(int n, int level) {
    return std::max(1, n >> std::min(level, 30));
}

// The (unnormalised) direction through the continuous texel position (x, y) of an n x n face.
glm::vec3 texelDirection(int face, int n, float x, float y) {
    return glsl::cubeFaceDirection(face, glm::vec2(x / float(n), y / float(n)));
}

// Texel (x, y) of `face`, where x or y may lie one texel past the face: such a tap reads the
// texel of the neighbouring face through the tap's direction (the face's plane extended).
// Past a corner (both out) there is no texel: the mean of the three texels at the corner.
glm::vec4 texelAcross(const CubeFaces& faces, int face, int x, int y) {
    const int n = faces[face].width;
    const bool inX = x >= 0 && x < n, inY = y >= 0 && y < n;
    if (inX && inY) return faces[face].rgba(x, y);
    if (!inX && !inY) {
        const int cx = std::clamp(x, 0, n - 1), cy = std::clamp(y, 0, n - 1);
        return (faces[face].rgba(cx, cy) + texelAcross(faces, face, x, cy) +
                texelAcross(faces, face, cx, y)) /
               3.0f;
    }
    const glm::vec3 uvf =
        glsl::cubeFaceUv(texelDirection(face, n, float(x) + 0.5f, float(y) + 0.5f));
    const int f = int(uvf.z);
    const int tx = std::clamp(int(std::floor(uvf.x * float(n))), 0, n - 1);
    const int ty = std::clamp(int(std::floor(uvf.y * float(n))), 0, n - 1);
    return faces[f].rgba(tx, ty);
}

// Bilinear at (u, v) of `face`, taps past the edges read across them.
glm::vec4 bilinearAcross(const CubeFaces& faces, int face, float u, float v) {
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

// RGB faces with a one-texel border holding what texelAcross reads there, so bilinear taps
// never leave the stored texels: the filter's inner loop, identical to bilinearAcross.
struct PaddedCube {
    int n = 0;
    std::array<std::vector<float>, 6> rgb; // (n + 2)^2 texels of 3 floats, row-major

    explicit PaddedCube(const CubeFaces& faces) : n(faces[0].width) {
        const int p = n + 2;
        for (int f = 0; f < 6; ++f) {
            rgb[f].resize(std::size_t(p) * p * 3);
            for (int y = -1; y <= n; ++y)
                for (int x = -1; x <= n; ++x) {
                    const glm::vec4 c = texelAcross(faces, f, x, y);
                    float* q = &rgb[f][(std::size_t(y + 1) * p + (x + 1)) * 3];
                    q[0] = c.r;
                    q[1] = c.g;
                    q[2] = c.b;
                }
        }
    }

    glm::vec3 bilinear(int face, float u, float v) const {
        const float fx = u * float(n) - 0.5f, fy = v * float(n) - 0.5f;
        const float x0f = std::floor(fx), y0f = std::floor(fy);
        const float ax = fx - x0f, ay = fy - y0f;
        // u, v in [0, 1] put x0 in [-1, n - 1]; clamp anyway against rounding.
        const int x0 = std::clamp(int(x0f), -1, n - 1) + 1,
                  y0 = std::clamp(int(y0f), -1, n - 1) + 1;
        const std::size_t stride = std::size_t(n + 2) * 3;
        const float* a = &rgb[face][std::size_t(y0) * stride + std::size_t(x0) * 3];
        const float* c = a + stride;
        const glm::vec3 top =
            glm::mix(glm::vec3(a[0], a[1], a[2]), glm::vec3(a[3], a[4], a[5]), ax);
        const glm::vec3 bottom =
            glm::mix(glm::vec3(c[0], c[1], c[2]), glm::vec3(c[3], c[4], c[5]), ax);
        return glm::mix(top, bottom, ay);
    }
};

// A level of m x m faces of `channels` floats a texel, rows in parallel: texel(face, x, y, q)
// writes texel (x, y) of `face` into q.
template <typename Texel> CubeFaces computeLevel(int m, int channels, const Texel& texel) {
    CubeFaces out;
    for (Image& img : out)
        img = Image(m, m, channels);
    tbb::parallel_for(tbb::blocked_range<int>(0, 6 * m), [&](const tbb::blocked_range<int>& r) {
        for (int row = r.begin(); row < r.end(); ++row) {
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

// One GGX sample in the frame of the lobe's axis (z): the reflected direction, its weight
// n.l, and the part of its filtered-importance-sampling mip level that does not depend on
// where it lands. FIS reads the mip whose texel covers the sample's share of the lobe,
//     lod = 0.5 log2(omegaSample / omegaTexel) + bias,  omegaSample = 1 / (count pdf(l)),
// with omegaTexel = (2/n)^2 / (1 + s^2 + t^2)^1.5 the level-0 texel at the sample's face
// coordinates (s, t): lodBase = 0.5 log2(omegaSample) - log2(2 / n) + bias, and the filter
// adds 0.75 log2(1 + s^2 + t^2).
struct LobeSample {
    glm::vec3 l;
    float weight;
    float lodBase;
};

double radicalInverse(std::uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return double(bits) * 2.3283064365386963e-10; // / 2^32
}

std::vector<LobeSample> lobeSamples(float roughness, int count, int n, float lodBias) {
    const double a = double(roughness) * roughness, a2 = a * a;
    std::vector<LobeSample> samples;
    for (int k = 0; k < count; ++k) {
        // Hammersley point, midpoint-stratified in the polar coordinate.
        const double xi = (k + 0.5) / count;
        const double phi = 2.0 * kPi * radicalInverse(std::uint32_t(k));
        // GGX: h ~ D(h) (n.h), cos^2 theta_h = (1 - xi) / (1 + (a^2 - 1) xi).
        const double cos2 = (1.0 - xi) / (1.0 + (a2 - 1.0) * xi);
        const double cosH = std::sqrt(cos2), sinH = std::sqrt(std::max(0.0, 1.0 - cos2));
        const double nDotL = 2.0 * cos2 - 1.0; // l = reflect(-n, h) since v = n
        if (!(nDotL > 0.0)) continue;
        const glm::dvec3 l(2.0 * cosH * sinH * std::cos(phi), 2.0 * cosH * sinH * std::sin(phi),
                           nDotL);
        // pdf over l: D (n.h) / (4 v.h) = D / 4 with v = n.
        const double t = (a2 - 1.0) * cos2 + 1.0;
        const double pdf = a2 / (kPi * t * t) / 4.0;
        const double omegaSample = 1.0 / (double(count) * pdf);
        const double lodBase = 0.5 * std::log2(omegaSample) - std::log2(2.0 / n) + lodBias;
        samples.push_back({glm::vec3(l), float(nDotL), float(lodBase)});
    }
    return samples;
}

// The GGX level of m x m faces from the input's mips.
CubeFaces filterLevel(const std::vector<PaddedCube>& mips, const std::vector<LobeSample>& lobe,
                      int m) {
    const int maxMip = int(mips.size()) - 1;
    return computeLevel(m, 4, [&](int face, int x, int y, float* q) {
        const glm::vec3 nrm =
            glm::normalize(texelDirection(face, m, float(x) + 0.5f, float(y) + 0.5f));
        // Any frame about the axis will do: the lobe is symmetric about it, and with the FIS
        // blur the estimate hardly depends on how the sample pattern is turned (the frame turns
        // abruptly only near the +-Y face centres, where up switches).
        const glm::vec3 up = std::fabs(nrm.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 tx = glm::normalize(glm::cross(up, nrm));
        const glm::vec3 ty = glm::cross(nrm, tx);
        glm::vec3 sum(0.f);
        float wsum = 0.f;
        for (const LobeSample& s : lobe) {
            const glm::vec3 l = s.l.x * tx + s.l.y * ty + s.l.z * nrm;
            const glm::vec3 uvf = glsl::cubeFaceUv(l);
            const float sc = 2.f * uvf.x - 1.f, tc = 2.f * uvf.y - 1.f;
            // The level-0 texel's solid angle here is (2/n)^2 / (1 + s^2 + t^2)^1.5.
            const float lod = std::clamp(s.lodBase + 0.75f * std::log2(1.f + sc * sc + tc * tc),
                                         0.f, float(maxMip));
            const int m0 = std::min(int(lod), maxMip), m1 = std::min(m0 + 1, maxMip);
            const int f = int(uvf.z);
            glm::vec3 c = mips[m0].bilinear(f, uvf.x, uvf.y);
            const float blend = lod - float(m0);
            if (blend > 0.f && m1 != m0) c = glm::mix(c, mips[m1].bilinear(f, uvf.x, uvf.y), blend);
            sum += s.weight * c;
            wsum += s.weight;
        }
        q[0] = sum.x / wsum;
        q[1] = sum.y / wsum;
        q[2] = sum.z / wsum;
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

    std::vector<PaddedCube> mips;
    for (const CubeFaces& mip : radianceMips(faces, solidAngleTable(n)))
        mips.emplace_back(mip);
    for (int level = 1; level < options.levels; ++level) {
        const int m = levelSize(n, level);
        const float r = ggxChainRoughness(level, options.levels);
        CubeFaces radiance = filterLevel(
            mips, lobeSamples(r, ggxChainSamples(level, options), n, options.lodBias), m);
        CubeFaces minMax = minMaxLevel(faces, m, options.dInf);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < m; ++y)
                for (int x = 0; x < m; ++x)
                    radiance[f].at(x, y)[3] = minMax[f].at(x, y)[0];
        chain.levels.push_back(std::move(radiance));
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
