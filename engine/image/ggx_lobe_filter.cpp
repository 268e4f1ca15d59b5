#include "engine/image/ggx_lobe_filter.h"

#include "engine/core/parallel_for.h"
#include "engine/math/cube_face.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/geometric.hpp>

namespace specula::ggx_filter {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The (unnormalised) direction through the continuous texel position (x, y) of an n x n face.
glm::vec3 texelDirection(int face, int n, float x, float y) {
    return glsl::cubeFaceDirection(face, glm::vec2(x / float(n), y / float(n)));
}

} // namespace

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

namespace {

// Four floats, one SIMD register: a texel's RGB and a zero. Arithmetic on it is per lane,
// each lane the same IEEE operations as the glm::vec3 code it replaces (the same bits).
using Rgbx = float __attribute__((vector_size(16)));

Rgbx loadRgbx(const float* p) {
    Rgbx v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

// RGB faces with a one-texel border holding what texelAcross reads there, so bilinear taps
// never leave the stored texels: the filter's inner loop, identical to bilinearAcross.
// Texels are padded to four floats so a tap is one load.
struct PaddedCube {
    int n = 0;
    std::array<std::vector<float>, 6> rgbx; // (n + 2)^2 texels of 4 floats, row-major

    explicit PaddedCube(const CubeFaces& faces) : n(faces[0].width) {
        const int p = n + 2;
        for (int f = 0; f < 6; ++f) {
            rgbx[f].resize(std::size_t(p) * p * 4);
            for (int y = -1; y <= n; ++y)
                for (int x = -1; x <= n; ++x) {
                    const glm::vec4 c = texelAcross(faces, f, x, y);
                    float* q = &rgbx[f][(std::size_t(y + 1) * p + (x + 1)) * 4];
                    q[0] = c.r;
                    q[1] = c.g;
                    q[2] = c.b;
                    q[3] = 0.f;
                }
        }
    }

    // glm::mix(glm::mix(a, b, ax), glm::mix(c, d, ax), ay), lane by lane.
    Rgbx bilinear(int face, float u, float v) const {
        const float fx = u * float(n) - 0.5f, fy = v * float(n) - 0.5f;
        const float x0f = std::floor(fx), y0f = std::floor(fy);
        const float ax = fx - x0f, ay = fy - y0f;
        // u, v in [0, 1] put x0 in [-1, n - 1]; clamp anyway against rounding.
        const int x0 = std::clamp(int(x0f), -1, n - 1) + 1,
                  y0 = std::clamp(int(y0f), -1, n - 1) + 1;
        const std::size_t stride = std::size_t(n + 2) * 4;
        const float* a = &rgbx[face][std::size_t(y0) * stride + std::size_t(x0) * 4];
        const float* c = a + stride;
        const Rgbx top = loadRgbx(a) * (1.f - ax) + loadRgbx(a + 4) * ax;
        const Rgbx bottom = loadRgbx(c) * (1.f - ax) + loadRgbx(c + 4) * ax;
        return top * (1.f - ay) + bottom * ay;
    }
};

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

// The lobe's samples as arrays (one loop over them per texel vectorises).
struct LobeSet {
    std::vector<float> lx, ly, lz, weight, lodBase;
    explicit LobeSet(const std::vector<LobeSample>& lobe) {
        for (const LobeSample& s : lobe) {
            lx.push_back(s.l.x);
            ly.push_back(s.l.y);
            lz.push_back(s.l.z);
            weight.push_back(s.weight);
            lodBase.push_back(s.lodBase);
        }
    }
    int size() const { return int(lx.size()); }
};

// Where the samples of one texel land: face, face coordinates, 1 + s^2 + t^2 (then its
// 0.75 log2, then the clamped mip level). Scratch of one thread.
struct LobeScratch {
    std::vector<float> u, v, q;
    std::vector<int> face;
    explicit LobeScratch(int count) : u(count), v(count), q(count), face(count) {}
};

// cubeFaceUv for the filter's finite, non-zero directions: the same face choice and the same
// arithmetic, so the same bits. Its clamp to [0, 1] is left out: |sc|, |tc| <= ma makes it a
// no-op. Selects of floats, not branches, so the loop over samples vectorises.
void landSamples(int count, const float* __restrict lx, const float* __restrict ly,
                 const float* __restrict lz, glm::vec3 tx, glm::vec3 ty, glm::vec3 nrm,
                 float* __restrict us, float* __restrict vs, float* __restrict qs,
                 int* __restrict faces) {
    for (int k = 0; k < count; ++k) {
        const float dx = lx[k] * tx.x + ly[k] * ty.x + lz[k] * nrm.x;
        const float dy = lx[k] * tx.y + ly[k] * ty.y + lz[k] * nrm.y;
        const float dz = lx[k] * tx.z + ly[k] * ty.z + lz[k] * nrm.z;
        const float ax = std::fabs(dx), ay = std::fabs(dy), az = std::fabs(dz);
        const bool onX = (ax >= ay) & (ax >= az), onY = !onX & (ay >= az);
        const bool px = dx >= 0.f, py = dy >= 0.f, pz = dz >= 0.f;
        const float ma = onX ? ax : (onY ? ay : az);
        const float scX = px ? -dz : dz, scZ = pz ? dx : -dx, tcY = py ? dz : -dz;
        const float sc = onX ? scX : (onY ? dx : scZ);
        const float tc = onY ? tcY : -dy;
        const float fX = px ? 0.f : 1.f, fY = py ? 2.f : 3.f, fZ = pz ? 4.f : 5.f;
        const float f = onX ? fX : (onY ? fY : fZ);
        const float u = 0.5f * (sc / ma) + 0.5f, v = 0.5f * (tc / ma) + 0.5f;
        const float s2 = 2.f * u - 1.f, t2 = 2.f * v - 1.f;
        us[k] = u;
        vs[k] = v;
        qs[k] = 1.f + s2 * s2 + t2 * t2;
        faces[k] = int(f);
    }
}

// The GGX level of m x m faces from the input's padded mips.
CubeFaces filterLevel(const std::vector<PaddedCube>& mips, const std::vector<LobeSample>& samples,
                      int m) {
    const int maxMip = int(mips.size()) - 1;
    const LobeSet lobe(samples);
    const int count = lobe.size();
    CubeFaces out;
    for (Image& img : out)
        img = Image(m, m, 4);
    parallelForRanges(0, 6 * m, [&](int begin, int end) {
        LobeScratch s(count);
        for (int row = begin; row < end; ++row) {
            const int face = row / m, y = row % m;
            for (int x = 0; x < m; ++x) {
                const glm::vec3 nrm =
                    glm::normalize(texelDirection(face, m, float(x) + 0.5f, float(y) + 0.5f));
                const glm::vec3 up =
                    std::fabs(nrm.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
                const glm::vec3 tx = glm::normalize(glm::cross(up, nrm));
                const glm::vec3 ty = glm::cross(nrm, tx);
                landSamples(count, lobe.lx.data(), lobe.ly.data(), lobe.lz.data(), tx, ty, nrm,
                            s.u.data(), s.v.data(), s.q.data(), s.face.data());
                for (int k = 0; k < count; ++k)
                    s.q[k] =
                        std::clamp(lobe.lodBase[k] + 0.75f * std::log2(s.q[k]), 0.f, float(maxMip));
                Rgbx sum = {0.f, 0.f, 0.f, 0.f};
                float wsum = 0.f;
                for (int k = 0; k < count; ++k) {
                    const float lod = s.q[k];
                    const int m0 = std::min(int(lod), maxMip), m1 = std::min(m0 + 1, maxMip);
                    const int f = s.face[k];
                    Rgbx c = mips[m0].bilinear(f, s.u[k], s.v[k]);
                    const float blend = lod - float(m0);
                    if (blend > 0.f && m1 != m0)
                        c = c * (1.f - blend) + mips[m1].bilinear(f, s.u[k], s.v[k]) * blend;
                    sum += lobe.weight[k] * c;
                    wsum += lobe.weight[k];
                }
                float* q = out[face].at(x, y);
                q[0] = sum[0] / wsum;
                q[1] = sum[1] / wsum;
                q[2] = sum[2] / wsum;
            }
        }
    });
    return out;
}

} // namespace

std::vector<CubeFaces> filterGgxLevels(const std::vector<CubeFaces>& mips,
                                       const GgxPrefilterOptions& options) {
    const int n = mips[0][0].width;
    std::vector<PaddedCube> padded;
    for (const CubeFaces& mip : mips)
        padded.emplace_back(mip);
    std::vector<CubeFaces> levels;
    for (int level = 1; level < options.levels; ++level) {
        const int m = std::max(1, n >> std::min(level, 30));
        const float r = ggxChainRoughness(level, options.levels);
        levels.push_back(filterLevel(
            padded, lobeSamples(r, ggxChainSamples(level, options), n, options.lodBias), m));
    }
    return levels;
}

} // namespace specula::ggx_filter
