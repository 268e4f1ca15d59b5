#pragma once
// Is a probe placed where a bake means something? Both bakes (distance and light field) ask
// once before tracing. Decided by measuring the scene with Embree from the probe centre, not
// by thresholds fitted to one scene: a few thousand evenly spread directions are traced and
//   - nothing to reflect (no environment geometry is met, by the spread directions nor by a
//     ray aimed at each object, and there is no sky)                             -> refused;
//     geometry met only by the aimed rays (too small to cover a direction)       -> warned;
//   - most of the geometry met shows its back (single-sided faces seen from behind: the probe
//     is inside a solid, or outside a closed room looking at the backs of its walls)  -> refused;
//     a tenth or more                                                            -> warned;
//   - the nearest hit closer than float precision separates from the surface (the probe
//     lies on it: zero distances no probe can store)                             -> refused;
//     within a thousandth of the scene size                                      -> warned;
//   - outside the bounds of all environment geometry and seeing it in under a quarter of the
//     directions (looking at the scene from afar rather than sitting in it)      -> warned.
// glTF doubleSided materials have legitimate back faces: they count as front.
#include "assetcooker/lib/scene/scene_markup.h"
#include "engine/ecs/registry.h"

#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

struct ProbePlacement {
    int directions = 0;     // traced
    int hits = 0;           // directions that meet environment geometry
    int aimedHits = 0;      // rays aimed at each object's bounds centre that meet geometry
    int backHits = 0;       // of those, the back face of single-sided geometry
    std::string backObject; // the environment object most of the back faces belong to
    float nearest = 0.f;    // metres to the nearest hit (0 when none)
    // The span of what the probe sees, metres: twice its farthest hit (the bounds' diagonal
    // when nothing is hit). Not the bounds of every node: one node 1e38 m away must not make
    // the room around the probe look like a speck on a surface. Double: such bounds overflow
    // float.
    double sceneSize = 0.0;
    float outside = 0.f;   // metres from the environment's bounds (0 inside)
    bool geometry = false; // the scene has environment geometry at all
};

ProbePlacement measureProbePlacement(ecs::Registry& registry, const SceneMarkup& markup,
                                     glm::vec3 centre, int directions = 4096);

// Throws Error naming the probe (its node, or the centre given on the command line) and the
// measured figure where the bake would be meaningless; returns warnings, one line each, where
// the placement is merely suspicious. `hasSky`: a sky panorama fills what no geometry covers.
std::vector<std::string> checkProbePlacement(ecs::Registry& registry, const SceneMarkup& markup,
                                             glm::vec3 centre, bool hasSky);

} // namespace specula
