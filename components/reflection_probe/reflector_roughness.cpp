#include "reflector_roughness.h"

#include "engine/image/sampling.h"
#include "engine/scene/components.h"

#include <algorithm>

namespace specula {

float roughnessAt(float factor, const Image* map, glm::vec2 uv) {
    if (!map) return factor;
    return std::clamp(factor * sampleBilinear(*map, uv, Wrap::Repeat).g, 0.f, 1.f);
}

float roughnessMapMin(const Image* map) {
    if (!map || map->channels < 2) return 1.f;
    float least = 1.f;
    for (std::size_t i = 1; i < map->pixels.size(); i += std::size_t(map->channels))
        least = std::min(least, map->pixels[i]);
    return std::clamp(least, 0.f, 1.f);
}

float roughnessMapMean(const Image* map) {
    if (!map || map->channels < 2 || map->pixels.empty()) return 1.f;
    double sum = 0.0;
    for (std::size_t i = 1; i < map->pixels.size(); i += std::size_t(map->channels))
        sum += double(map->pixels[i]);
    const double texels = double(map->pixels.size() / std::size_t(map->channels));
    return float(std::clamp(sum / texels, 0.0, 1.0));
}

MaterialRoughness materialRoughness(const ecs::Registry& registry,
                                    const std::vector<ecs::Entity>& meshes) {
    const MaterialData* only = nullptr;
    bool several = false;
    float sum = 0.f;
    int count = 0;
    for (ecs::Entity e : meshes) {
        const Mesh* mesh = registry.find<Mesh>(e);
        if (!mesh) continue;
        for (const Primitive& p : mesh->primitives) {
            if (!p.material) continue;
            if (only && only != p.material.get()) several = true;
            only = p.material.get();
            sum += p.material->roughness();
            ++count;
        }
    }
    MaterialRoughness out;
    if (!only) return out;
    if (several) {
        out.factor = std::clamp(sum / float(count), 0.f, 1.f);
        return out;
    }
    out.factor = only->roughnessFactor;
    out.map = only->metallicRoughnessTexture;
    return out;
}

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
