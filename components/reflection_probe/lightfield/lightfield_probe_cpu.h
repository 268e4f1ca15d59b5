#pragma once
// The CPU twin of the light-field shader: the same lookup code
// (shaders/lightfield_lookup.glsl.h) compiled as C++ over the cooked atlas, with bilinear
// fetches that read what the GPU reads (sRGB texels decoded to linear before filtering, BC1
// decoded first, clamped to the layer). Tests hold the shader to it pixel by pixel. The glossy
// lookup (shaders/lightfield_glossy.glsl.h) reads the mips of lightfield_mips.h, made on its
// first call.
#include "components/reflection_probe/lightfield/lightfield_asset.h"

#include <array>
#include <cstdint>
#include <memory>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace specula {

// The glossy lookup's settings (the shader's uniforms; see shaders/lightfield_glossy.glsl.h).
// The defaults are what the shader uses; the others exist for the measurements
// (tests/probe/lightfield_glossy_test.cpp; room, NUM 8, RES 64, roughness 0.35, against the
// GGX truth): K = 16 rays at every pixel. 8 rays lose 1.2-1.6 dB, 32 gain 1.0-1.2 dB for twice
// the fetches; the mips alone (K = 1) lose 5 dB; the same 16 rays without mips lose 0.8-1.0 dB,
// and rays without mips alias textured surfaces (on the synthetic walls 32 rays at level 0 err
// 1.4-3.2x as much as these 16 with mips). Level bias log2(2 / sqrt(12)): a level-k trilinear
// read blurs with a standard deviation of 2^k / 2 texels (a 2^k box, then the bilinear tent), a
// ray's square share of side s has s / sqrt(12); the bias makes the two equal.
// K per pixel (tests/probe/lightfield_glossy_rays_test.cpp, the same room, both placements):
// the footprint rule with 2 rays per texel of the lobe's width, at most 16, is within 0.05 dB of
// K = 16 everywhere for 8 / 40 / 115 fetches a pixel at r = 0.05 / 0.1 / 0.2 against 68 / 84 /
// 118; at r >= 0.35 every pixel asks for 16 or more. A cap of 32 there gains 1.0-1.2 dB at
// r = 0.35, 2.1 at 0.5, 3.5-3.6 at 0.75 for twice the fetches (and 0.03-0.04 dB at r = 0.2 for
// 1.3x): the cap stays the old fixed K, 16, so the pass costs at most what CHANGELOG.md measured.
inline constexpr int kLightFieldGlossyRays = 16;
inline constexpr float kLightFieldGlossyLevelBias = -0.7925f;
inline constexpr float kLightFieldGlossyRaysPerTexel = 2.f;
struct LightFieldGlossyOptions {
    int rays = kLightFieldGlossyRays;             // the most lobe rays a pixel takes: 1 or even
    float levelBias = kLightFieldGlossyLevelBias; // added to each ray's mip level
    bool mips = true;                             // false: every ray at level 0
    bool footprint = true; // K per pixel from the lobe's footprint; false: K = rays everywhere
    float raysPerTexel = kLightFieldGlossyRaysPerTexel; // the rule's factor (see the shader)
};

// Continuous indices of a ray's slab lookup, before clamping (exposed for the coverage tests).
struct LightFieldCoords {
    int slab = 0;
    glm::vec2 camera{0.f};
    glm::vec2 pixel{0.f};
};

class CpuLightFieldProbe {
public:
    // disparity: pixels per camera step for all slabs; < 0 or NaN: the cooked per-slab values.
    explicit CpuLightFieldProbe(const LightFieldAsset& asset, float disparity = -1.f);
    ~CpuLightFieldProbe();

    // p: cell-local reflector point, d: reflected direction (need not be unit).
    glm::vec3 radiance(glm::vec3 p, glm::vec3 d) const;
    LightFieldCoords coords(glm::vec3 p, glm::vec3 d) const;

    // The normalised GGX filter of a reflector of perceptual roughness `roughness` at p with
    // normal n (either side) and mirror direction lhat (unit): lightFieldGlossyRadiance.
    // Roughness <= 0 or NaN: radiance(p, lhat), bit for bit. Thread-safe.
    glm::vec3 glossyRadiance(glm::vec3 p, glm::vec3 lhat, glm::vec3 n, float roughness,
                             const LightFieldGlossyOptions& options = {}) const;
    // The rays K the glossy lookup takes at this pixel (lightFieldLobeRays); 0 for a mirror
    // (roughness <= 0 or NaN: the mirror lookup, no lobe).
    int glossyRays(glm::vec3 p, glm::vec3 lhat, glm::vec3 n, float roughness,
                   const LightFieldGlossyOptions& options = {}) const;
    // What the shader writes for a reflector (before Fresnel): the filter times the GGX
    // directional albedo E(|n.lhat|, roughness) when roughness > 0, else the mirror lookup.
    glm::vec3 reflectedRadiance(glm::vec3 p, glm::vec3 lhat, glm::vec3 n, float roughness,
                                const LightFieldGlossyOptions& options = {}) const;
    // The deepest mip level the glossy lookup reads (lightFieldMaxLevel).
    int maxLevel() const;
    // Bilinear fetches the lookups of every twin have made on the calling thread so far (a
    // running count: the cost figures take differences).
    static std::uint64_t fetchCount();

    // The disparities the lookup uses (cooked or the override).
    const std::array<float, 6>& disparities() const { return disparity_; }

private:
    struct Twin;
    std::unique_ptr<Twin> twin_;
    std::array<float, 6> disparity_{};
};

// Effective per-slab disparity: the override when it is finite and >= 0, else the cooked.
std::array<float, 6> effectiveDisparities(const LightFieldAsset& asset, float override_);

} // namespace specula
