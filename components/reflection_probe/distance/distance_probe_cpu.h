#pragma once
// The CPU twin of the distance-cubemap shader: the same lookup code
// (shaders/distance_lookup.glsl.h), compiled as C++ over the cooked images, with texture
// fetches that read what the GPU reads (bilinear radiance, nearest distance, clamp to the
// face edge). Tests hold the shader to it pixel by pixel.
#include "components/reflection_probe/distance/distance_lookup_config.h"

#include <memory>

namespace specula {

class CpuDistanceProbe {
public:
    CpuDistanceProbe(const DistanceProbeAsset& asset, DistanceLookupConfig config);
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

    // The asset's sky along dir, as the shader's fetchSky reads it (black without one).
    glm::vec3 sky(glm::vec3 dir) const;

    const DistanceLookupConfig& config() const { return config_; }

private:
    struct Twin;
    std::unique_ptr<Twin> twin_;
    DistanceLookupConfig config_;
};

} // namespace specula
