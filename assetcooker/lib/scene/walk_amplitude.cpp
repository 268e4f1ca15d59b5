#include "walk_amplitude.h"

#include "engine/scene/mesh_bounds.h"

#include <algorithm>

namespace specula {

float walkAmplitude(const ProbeScene& scene, glm::vec3 currentOffset) {
    const float cellSize = markupCellSize(scene.markup);
    const float half = 0.5f * cellSize;
    const Aabb cell =
        Aabb::cube(markupProbeCentre(scene.registry, scene.markup, scene.loaded), half);
    float slack = half;
    for (ecs::Entity e : scene.markup.mirrorEntities)
        slack = std::min(
            slack, -meshWorldBounds(scene.registry, e).translated(-currentOffset).overhang(cell));
    return std::clamp(slack, 0.f, 0.2f * cellSize);
}

} // namespace specula
