#include "reflector_roughness_maps.h"

#include <algorithm>

namespace specula {

ReflectorRoughnessMaps::ReflectorRoughnessMaps(const SceneMarkup& markup) {
    for (const ReflectorMarkup& r : markup.reflectors) {
        if (!r.roughnessMap) continue;
        const float mean = roughnessMapMean(r.roughnessMap.get());
        for (const ecs::Entity mesh : r.meshes)
            maps_[mesh] = Map{r.roughnessMap, mean};
    }
}

const Image* ReflectorRoughnessMaps::of(ecs::Entity mesh) const {
    const auto it = maps_.find(mesh);
    return it == maps_.end() ? nullptr : it->second.image.get();
}

float ReflectorRoughnessMaps::at(float factor, ecs::Entity mesh, glm::vec2 uv) const {
    return roughnessAt(factor, of(mesh), uv);
}

float ReflectorRoughnessMaps::mean(float factor, ecs::Entity mesh) const {
    const auto it = maps_.find(mesh);
    return it == maps_.end() ? factor : std::clamp(factor * it->second.mean, 0.f, 1.f);
}

} // namespace specula
