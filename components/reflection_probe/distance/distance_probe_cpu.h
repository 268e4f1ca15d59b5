#pragma once
// The CPU twin of the distance-cubemap shader: the same lookup code
// (shaders/distance_lookup.glsl.h), compiled as C++ over the cooked images, with texture
// fetches that read what the GPU reads (bilinear radiance, nearest distance, clamp to the
// face edge). Tests hold the shader to it pixel by pixel.
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "engine/image/ggx_prefilter.h"

#include <algorithm>
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
    // seenRadiance with the radiance of glossySample's chain read at the same hit (the
    // verdict is the mirror ray's; shaders/distance_glossy_seen.glsl.h): what a level blends
    // for a rough reflector. Roughness <= 0 is seenRadiance exactly. Throws Error when the
    // probe was made without a chain.
    Seen glossySeen(glm::vec3 x, glm::vec3 lhat, float roughness) const;

    // The composite's (layer 0) lookup by params.method alone, as radiance() runs it without
    // layers, with the distance t along the ray to what it found (the glossy lookup reads
    // its chain there): the box exit for boxproj; d_inf for envmap and when nothing was hit
    // (hit = false, radiance from the sky).
    struct CompositeHit {
        glm::vec3 radiance{0.f};
        float t = 0.f;
        bool hit = false;
        int fetches = 0;
        glm::vec3 at{0.f}; // probe-local point whose texel gave the radiance (LayerHit::at)
    };
    CompositeHit compositeHit(glm::vec3 x, glm::vec3 lhat) const;
    // The configured lookup's hit, as radiance() finds it (layered: the nearest over the
    // object layers; the experiment's search when set), with its fetches (the sky's included).
    CompositeHit lookupHit(glm::vec3 x, glm::vec3 lhat) const;
    // Layered mode: object layer `layer` (1..layerCount) alone, searched by its method over
    // the ray's stretch inside its box as the layered loop searches it; radiance 0 and
    // t = d_inf when it finds nothing (no sky). Throws Error for a layer not in the lookup.
    CompositeHit objectLayerHit(int layer, glm::vec3 x, glm::vec3 lhat) const;

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

    // Controlled experiments of the bench's error budget
    // (sandbox/lib/flavours/distance/error_budget.h): each removes one source of error from every
    // lookup of the twin (radiance(), lookupHit() and the rest). All off by default, where the twin
    // reads exactly what the shader reads. Set before looking up, never while another thread does.
    struct Experiment {
        // The method's own way to the hit (a search to d_e with its step budget, one step at
        // d-bar, the box wall, or none at all for envmap) replaced by the exact first
        // crossing along the stored distances (a dense projection-uniform march, then
        // bisection to float precision; lookupExact in the shared lookup, run through the
        // shader's own layer loop), on the composite or, layered, on every object layer:
        // what the method's approximation of the hit costs.
        bool exactSearch = false;
        // Radiance filtered only over the texels whose stored distance agrees with the
        // nearest texel's (sameSurfaceSlack): never a blend across a depth discontinuity (a
        // silhouette), elsewhere the GPU's bilinear fetch.
        bool sameSurfaceRadiance = false;
    };
    // Texels of one surface differ in distance by at most this share of it: 5%, or what a
    // surface inclined 80 degrees to the centre's view changes from one texel to the next
    // (a texel subtends about 2 / faceRes radians, tan 80 degrees is 5.7), whichever is larger.
    static float sameSurfaceSlack(int faceRes) {
        return faceRes > 0 ? std::max(0.05f, 12.f / float(faceRes)) : 0.05f;
    }
    void setExperiment(const Experiment& e);
    const Experiment& experiment() const { return experiment_; }

    // What the probe centre sees in the direction of probe-local point h (a ground truth's
    // hit): `seen` when a layer holds a surface at |h| there (one of the 2 x 2 texels around
    // the direction within kSeenSlack |h| + two texels' span of |h|, which a surface inclined
    // to the centre's view spans), its radiance read from that layer; otherwise the centre
    // sees something else in front (a disocclusion) and `radiance` is what it sees there.
    // Layered: the object layers; otherwise the composite.
    struct CentreView {
        glm::vec3 radiance{0.f};
        bool seen = false;
        int layer = 0;
    };
    static constexpr float kSeenSlack = 0.03f;
    CentreView centreView(glm::vec3 h) const;

    const DistanceLookupConfig& config() const { return config_; }

private:
    struct Twin;
    std::unique_ptr<Twin> twin_;
    DistanceLookupConfig config_;
    std::shared_ptr<const CubeChain> glossy_;
    Experiment experiment_;
};

} // namespace specula
