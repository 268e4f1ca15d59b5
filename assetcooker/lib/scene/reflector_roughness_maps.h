#pragma once
// Per-mesh roughness maps of a scene's reflectors, from its markup: the tools' side of
// reflector_roughness.h (the runtime's twin of the shaders' roughness read).
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/system/reflector_roughness.h"

#include <memory>
#include <unordered_map>

namespace specula {

// The reflector meshes' roughness maps (ReflectorMarkup::roughnessMap), for the sandbox's
// per-pixel roughness (the glossy bench, the level walk), where --roughness sets every reflector's
// factor; the truth reads it from many threads at once (const only).
class ReflectorRoughnessMaps {
public:
    explicit ReflectorRoughnessMaps(const SceneMarkup& markup);
    bool empty() const { return maps_.empty(); }
    // The mesh's map, null where its reflector's roughness is uniform.
    const Image* of(ecs::Entity mesh) const;
    // factor x the mesh's map at uv (roughnessAt); the factor on a uniform reflector.
    float at(float factor, ecs::Entity mesh, glm::vec2 uv) const;
    // factor x the mean of the mesh's map (its G channel, as MaterialData::roughnessTextureMean
    // is taken), clamped to [0, 1]; the factor on a uniform reflector.
    float mean(float factor, ecs::Entity mesh) const;

private:
    struct Map {
        std::shared_ptr<const Image> image;
        float mean = 1.f;
    };
    std::unordered_map<ecs::Entity, Map> maps_;
};

} // namespace specula
