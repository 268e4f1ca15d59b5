#pragma once
// A baked level of distance probes (level_index.h) looked up on the CPU: the twin of the
// level shader (DistanceLevelStore), running the same blend code
// (shaders/distance_level_blend.glsl.h). Each reflector point blends up to K probes three
// ways: the nearest probe alone; engine-style (the influence volumes, blend distances and
// priorities of probe_volume.h, the rest from the sky); and by visibility, where a probe
// counts only when it sees the reflector point and the hit its lookup proposes
// (shaders/distance_seen.glsl.h), so a probe behind a wall adds nothing. Every probe runs
// the single-layer twin of the shader with the given method. A level made with its glossy
// chains (issue 14) also looks up rough reflectors: each probe's share is its own glossy
// sample (the chain read at its own hit, the footprint level there), blended with the
// mirror's weights (shaders/distance_glossy_seen.glsl.h).
#include "components/reflection_probe/distance/distance_level.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "components/reflection_probe/level_index.h"

#include <memory>
#include <string>
#include <vector>

namespace specula {

struct LevelSample {
    glm::vec3 radiance{0.f};
    std::vector<std::pair<int, float>> weights; // (probe index, weight) > 0
    float sky = 0.f;                            // weight of the sky
    int fetches = 0;
    // Visibility: probes with influence here that did not see the hit; `fallback` when none
    // did and the engine-style weights were used instead.
    int hidden = 0;
    bool fallback = false;
    bool outside = false; // p lies in no influence volume: the nearest probe answered
    // Visibility: the seen probes' influence x visibility, summed (at most 1); below 1 the
    // answer is that share of the seen probes' blend and the rest the engine's.
    float confidence = 0.f;
};

class CpuDistanceLevel {
public:
    // Reads DIR/level.json and every probe it lists (the distance flavour only); throws Error
    // naming the file and field. `settings.method` must rectify or project the composite
    // (envmap, boxproj, bisection, secant). `glossy`: every probe also gets its composite's
    // GGX chain (glossyChainOf: the cooked levels, else prefiltered here, as the store does),
    // which rough lookups need.
    CpuDistanceLevel(const std::string& levelIndexPath, const DistanceProbe& settings,
                     bool glossy = false);
    ~CpuDistanceLevel();

    // Radiance reflected at world point `p` along unit `lhat`; k in 1 .. kMaxLevelK.
    // `roughness` (perceptual, as Reflector::roughness): > 0 reads each probe's chain, the
    // normalised prefiltered lighting (the shader multiplies the GGX albedo outside); a level
    // made with chains runs the glossy code at every roughness (0 is the mirror exactly).
    // Throws Error for a rough lookup of a level made without chains.
    LevelSample radiance(glm::vec3 p, glm::vec3 lhat, LevelBlend blend, int k,
                         float roughness = 0.f) const;
    bool glossy() const { return glossy_; }
    // Probe i's chain (blend-order index as volumes()); null without glossy.
    const CubeChain* glossyChain(int i) const { return twins_[std::size_t(i)]->glossyChain(); }

    // Probe i's own lookup of the ray from world point p along lhat, with its verdict.
    CpuDistanceProbe::Seen seen(int i, glm::vec3 p, glm::vec3 lhat) const;

    const std::vector<ProbeVolume>& volumes() const { return volumes_; }
    // The probe whose position is nearest to p (ties: the first in blend order).
    int nearest(glm::vec3 p) const;
    // Probe indices in blend order (probe_volume.h blendsBefore), as the shader walks them.
    const std::vector<int>& blendOrder() const { return order_; }

private:
    std::vector<ProbeVolume> volumes_;
    std::vector<int> order_;
    std::vector<std::unique_ptr<DistanceProbeAsset>> assets_;
    std::vector<std::unique_ptr<CpuDistanceProbe>> twins_;
    std::string path_;
    bool glossy_ = false;
};

} // namespace specula
