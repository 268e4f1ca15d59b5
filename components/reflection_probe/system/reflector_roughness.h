#pragma once
// A reflector's GGX roughness at a point of its surface (alpha = roughness^2): its roughness
// factor, times its roughness map's G channel at the point's TEXCOORD_0 where it has one
// (glTF's metallicRoughnessTexture, linear). The CPU twin of the reflector shaders'
// HAS_ROUGHNESS_MAP read (reflector_roughness.glsl.h): the map is sampled as the GL texture
// is, GL_LINEAR without mipmaps and GL_REPEAT on both axes (sampleBilinear, Wrap::Repeat).
#include "engine/ecs/registry.h"
#include "engine/image/image.h"

#include <memory>
#include <vector>

#include <glm/vec2.hpp>

namespace specula {

// factor x map(uv).g, clamped to [0, 1]; the factor alone without a map.
float roughnessAt(float factor, const Image* map, glm::vec2 uv);

// The smallest roughness the map holds (its G channel), 1 without a map: factor x this is
// the sharpest lobe the reflector shows.
float roughnessMapMin(const Image* map);
// The mean of its G channel over its texels (as MaterialData::roughnessTextureMean is taken),
// 1 without a map: factor x this is the one roughness a reflector took before maps were read.
float roughnessMapMean(const Image* map);

// Where a reflector takes its roughness from its meshes' materials: the one material every
// primitive of `meshes` shares gives its factor and its metallic-roughness texture (null when
// it has none); primitives of different materials give their mean roughness() and no map
// (one map cannot stand for several materials).
struct MaterialRoughness {
    float factor = 0.f;
    std::shared_ptr<const Image> map;
};
MaterialRoughness materialRoughness(const ecs::Registry& registry,
                                    const std::vector<ecs::Entity>& meshes);

} // namespace specula
