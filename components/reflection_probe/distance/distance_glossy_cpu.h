#pragma once
// Glossy reflections from a distance probe, on the CPU (issue 14): the probe's composite
// (layer 0) with its GGX prefiltered chain (engine/image/ggx_prefilter.h), read at a
// direction and a level chosen four ways: what engines do (direction only, or box-projected,
// with the level from roughness alone), and the distance probe's mirror search for the hit
// followed by the level from roughness alone or from the lobe's footprint at the hit
// (shaders/distance_glossy.glsl.h). Roughness 0 is the mirror lookup of CpuDistanceProbe,
// bit for bit.
//
// Three modes are the shader's glossy path of a method (CpuDistanceProbe::glossySample, the
// code of shaders/distance_glossy_lookup.glsl.h): EnvmapChain is envmap's, BoxprojChain
// boxproj's, RectifiedFootprint that of the search method (bisection or secant).
// RectifiedRoughnessLevel, the search with the level from roughness alone, exists here only,
// as the comparison that shows what the footprint level buys.
//
// Radiance is the prefiltered (split-sum) lighting term only: the reflector's directional
// albedo and Fresnel multiply it outside, as in the shader.
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/image/ggx_prefilter.h"

#include <array>
#include <memory>

namespace specula {

enum class GlossyMode {
    EnvmapChain,             // direction only, level by roughness (Filament-style)
    BoxprojChain,            // box-projected direction, level by roughness (Unity, Godot)
    RectifiedRoughnessLevel, // the mirror search's hit direction, level by roughness
    RectifiedFootprint,      // the same direction, level by the lobe's footprint at the hit
};
inline constexpr std::array<GlossyMode, 4> kGlossyModes{
    GlossyMode::EnvmapChain, GlossyMode::BoxprojChain, GlossyMode::RectifiedRoughnessLevel,
    GlossyMode::RectifiedFootprint};
const char* glossyModeName(GlossyMode mode);

// The half-width (radians) of the GGX lobe of `alpha` (= roughness^2) that the footprint
// level is taken from: the shader's glossyLobeHalfAngle, for the planner.
float glossyLobeHalfAngle(float alpha);

class CpuGlossyDistanceProbe {
public:
    // `search`: the rectified modes' method (Bisection or Secant; else Error) and d_e. The
    // chain is glossyChainOf(asset, prefilter): the cooked levels, else the composite
    // prefiltered here. The asset must outlive the probe.
    explicit CpuGlossyDistanceProbe(const DistanceProbeAsset& asset,
                                    const DistanceProbe& search = {},
                                    const GgxPrefilterOptions& prefilter = {});

    struct Sample {
        glm::vec3 radiance{0.f};
        float level = 0.f; // chain level read (0 at roughness 0: the mirror lookup)
        float t = 0.f;     // along the ray to the hit the lookup read (d_inf: none, direction only)
        bool hit = false;  // a surface was found (always for envmap and boxproj)
    };
    // x: probe-local reflector point, lhat: unit mirror direction (the lobe's centre),
    // roughness: perceptual (alpha = roughness^2), clamped to [0, 1]; <= 0 or NaN: a mirror.
    Sample sample(glm::vec3 x, glm::vec3 lhat, float roughness, GlossyMode mode) const;
    glm::vec3 radiance(glm::vec3 x, glm::vec3 lhat, float roughness, GlossyMode mode) const {
        return sample(x, lhat, roughness, mode).radiance;
    }

    const CubeChain& chain() const { return *chain_; }

private:
    const CpuDistanceProbe& mirror(GlossyMode mode) const;

    std::shared_ptr<const CubeChain> chain_; // first: the probes below share it
    CpuDistanceProbe envmap_, boxproj_, rectified_;
};

} // namespace specula
