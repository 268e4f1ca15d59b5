#pragma once
// Bakes a distance-cubemap probe with Embree: for every texel of every face, the ray from
// the probe centre gives the radiance (house shading, same as the ground truth) and the
// exact Euclidean distance. Layer 0 holds the whole environment with the sky where nothing
// is hit; then one layer per environment object, sorted near to far.
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/ecs/registry.h"
#include "engine/image/ggx_prefilter.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace specula {

struct DistanceBakeOptions {
    glm::vec3 centre{0.f};
    int faceRes = 128;
    const Image* sky = nullptr; // equirectangular; black when null
    // Reflectors move within this distance of the centre; D must reach past them.
    float reflectorReach = 1.f;
    // World box the lookup's box projection assumes; default: the environment's bounds.
    std::optional<Aabb> proxy;
    // A layer covering at least this solid angle is marked for per-pixel rectification, a
    // smaller one for the average-distance correction (docs/design.md §4), unless `layers` says.
    float rectifySolidAngle = 0.379f;
    // The layers to bake, near to far, each a group of environment objects with its lookup
    // method (the effect plan). Empty: one layer per object, sorted by nearest distance.
    struct LayerSpec {
        std::string name;
        std::vector<std::string> objects;
        std::string method;
    };
    std::vector<LayerSpec> layers;
    bool withSky = true;                  // false: the composite sees black where nothing is hit
    bool compositeOnly = false;           // bake no object layers (the plan needs one lookup only)
    std::string compositeMethod;          // the composite's planned method (empty: by solid angle)
    std::function<void(double)> progress; // fraction done, from the baking thread
    std::function<bool()> cancelled;      // polled between rows; true aborts with Error
    // Where the probe placement's warnings go (checkProbePlacement); null: dropped. A
    // placement that makes the bake meaningless throws Error instead.
    std::vector<std::string>* warnings = nullptr;
};

DistanceProbeAsset bakeDistanceProbe(ecs::Registry& registry, const SceneMarkup& markup,
                                     const DistanceBakeOptions& options);

// Glossy reflectors (issue 14). Whether any reflector of the scene has a roughness > 0: what a
// glossy bake on Auto asks (a scene of mirrors pays nothing for the chain).
bool hasGlossyReflector(const SceneMarkup& markup);

// The composite's GGX prefiltered chain above level 0 into asset.glossyLevels: prefilterGgx
// of layer 0 with `options` (its levels, level 0 included; the default 6 gives 5 glossy
// levels, perceptual roughness 0.2 .. 1, the chain a glossy lookup builds itself when an
// asset has none) and the asset's d_inf. Call after bakeDistanceProbe (d_inf is set).
void prefilterComposite(DistanceProbeAsset& asset, const GgxPrefilterOptions& options = {});

} // namespace specula
