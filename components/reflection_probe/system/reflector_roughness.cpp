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

} // namespace specula
