#pragma once
// The rays a measured effect plan scores its candidates on: a stratified, seeded sample of
// reflected rays leaving the reflectors, with the exact answer along each (Embree, the
// environment only: what a probe can hold).
//
// Origins: points on the reflectors' triangles, area-weighted, displaced by a translation
// drawn uniformly over the cell the reflectors move in (markupCellSize, centred on the
// probe) and pulled back within `reach` of the centre, the bound the bake sizes D for.
// Directions: a share of the draws (the plan gives half, plan_measure.h) reflect the view
// from the scene's camera, the views the scene states; the rest are cosine-weighted about
// the surface normal, the views it does not state. A reflector seen from anywhere in front
// of it covers pixels in proportion to its projected area, cos(view angle), and a mirror's
// reflected direction makes the same angle with the normal as the view: the cosine-weighted
// hemisphere is the distribution of reflected rays over views spread evenly around the
// reflector. The hemisphere alone underweights what the camera sees; the camera alone
// knows nothing of where else a player stands.
// Stratification: Latin hypercube over the eight dimensions (triangle, two barycentrics,
// three of displacement, two of direction), strata permuted by a seeded generator of our own
// (std::mt19937 bits, Fisher-Yates): the same seed gives the same rays on every platform.
#include "assetcooker/lib/scene/scene_markup.h"
#include "engine/ecs/registry.h"
#include "engine/image/image.h"

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

struct PlanRay {
    glm::vec3 origin{0.f}; // world space, on a (displaced) reflector
    glm::vec3 dir{0.f};    // unit reflected direction
    glm::vec3 truth{0.f};  // environment-only radiance along the ray (Embree)
};

struct PlanRayOptions {
    int count = 4096;
    std::uint32_t seed = 1;
    glm::vec3 centre{0.f};
    float cellSize = 1.5f; // the translation range of the reflectors, per axis
    float reach = 1.f;     // origins stay within this distance of the centre
    const Image* sky = nullptr;
    // View points (the scene's camera): this share of the rays reflects the view from one of
    // them (round robin) instead of a cosine-weighted direction; a draw facing away from its
    // eye, or hidden from it by the environment, is dropped.
    std::vector<glm::vec3> eyes;
    float viewShare = 0.f;
};

struct PlanRaySample {
    std::vector<PlanRay> rays;
    int rejected = 0;  // draws whose origin the environment hides from the centre
    double area = 0.0; // the reflectors' total area, m^2
};

// Empty when the markup has no reflector triangle. Needs updateWorldTransforms first.
PlanRaySample samplePlanRays(ecs::Registry& registry, const SceneMarkup& markup,
                             const PlanRayOptions& options);

} // namespace specula
