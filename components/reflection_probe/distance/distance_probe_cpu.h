#pragma once
// The CPU twin of the distance-cubemap shader: the same lookup code
// (shaders/distance_lookup.glsl.h), compiled as C++ over the cooked images, with texture
// fetches that read what the GPU reads (bilinear radiance, nearest distance, clamp to the
// face edge). Tests hold the shader to it pixel by pixel.
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "engine/image/ggx_prefilter.h"

#include <memory>

namespace specula {

class CpuDistanceProbe {
public:
    // `glossy`: the composite's prefiltered chain (glossyChainOf), needed by glossySample
    // only; the asset must outlive the probe.
    CpuDistanceProbe(const DistanceProbeAsset& asset, DistanceLookupConfig config,
                     std::shared_ptr<const CubeChain> glossy = nullptr);
    ~CpuDistanceProbe();

    // x: probe-local reflector point, lhat: unit reflected direction. Adds the texture
    // fetches spent to `fetches`. `sawSky`: set when no layer was hit and the distant sky
    // answered.
    glm::vec3 radiance(glm::vec3 x, glm::vec3 lhat, int& fetches, bool* sawSky = nullptr) const;

    // The composite's single-layer lookup with whether the probe sees what it proposes
    // (shaders/distance_seen.glsl.h): what blending probes by visibility weighs.
    struct Seen {
        glm::vec3 radiance{0.f};
        float visibility = 0.f; // in [0, 1]
        bool seen = false;      // visibility >= 0.5
        int fetches = 0;
        float t = 0.f; // along the ray to the hit it proposes (d_inf: the sky)
    };
    Seen seenRadiance(glm::vec3 x, glm::vec3 lhat) const;

    // The composite's (layer 0) lookup by params.method alone, as radiance() runs it without
    // layers, with the distance t along the ray to what it found (the glossy lookup reads
    // its chain there): the box exit for boxproj; d_inf for envmap and when nothing was hit
    // (hit = false, radiance from the sky).
    struct CompositeHit {
        glm::vec3 radiance{0.f};
        float t = 0.f;
        bool hit = false;
        int fetches = 0;
    };
    CompositeHit compositeHit(glm::vec3 x, glm::vec3 lhat) const;

    // The shader's glossy path (HAS_GLOSSY, shaders/distance_glossy_lookup.glsl.h) for a
    // reflector of perceptual roughness `roughness`: the search of the configured method (the
    // nearest layer hit in layered mode), then the chain read at the hit direction with the
    // footprint level (searching methods, layered) or the roughness level (envmap, boxproj,
    // and rays that hit nothing). Roughness <= 0 is radiance() exactly. Throws Error when
    // the probe was made without a chain.
    struct GlossySample {
        glm::vec3 radiance{0.f};
        float level = 0.f; // chain level read (0 for a mirror)
        float t = 0.f;     // along the ray to the hit (d_inf: none, or envmap)
        bool hit = false;
        int fetches = 0;
    };
    GlossySample glossySample(glm::vec3 x, glm::vec3 lhat, float roughness) const;
    glm::vec3 glossyRadiance(glm::vec3 x, glm::vec3 lhat, float roughness) const {
        return glossySample(x, lhat, roughness).radiance;
    }
    const CubeChain* glossyChain() const { return glossy_.get(); }

    // The asset's sky along dir, as the shader's fetchSky reads it (black without one).
    glm::vec3 sky(glm::vec3 dir) const;

    const DistanceLookupConfig& config() const { return config_; }

private:
    struct Twin;
    std::unique_ptr<Twin> twin_;
    DistanceLookupConfig config_;
    std::shared_ptr<const CubeChain> glossy_;
};

} // namespace specula
