#pragma once
// Plain component structs produced by the scene loader. They hold data, never GPU handles:
// each system that draws them keeps its own GPU copy.
#include "engine/ecs/entity.h"
#include "engine/image/image.h"
#include "engine/math/aabb.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace specula {

struct Name {
    std::string value;
};

// Local TRS relative to `parent`; `world` is refreshed by updateWorldTransforms().
struct Transform {
    glm::vec3 translation{0.f};
    glm::quat rotation{1.f, 0.f, 0.f, 0.f};
    glm::vec3 scale{1.f};
    ecs::Entity parent = ecs::kNullEntity;
    glm::mat4 world{1.f};

    glm::mat4 local() const;
};

struct MeshData {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;     // generated (area-weighted) when the asset has none
    std::vector<glm::vec2> uvs;         // empty when the asset has none
    std::vector<std::uint32_t> indices; // triangle list
    // Local bounds; empty until the builder sets them (the glTF loader does), so a mesh
    // built without them is told apart from one at the origin (see localBounds()).
    glm::vec3 boundsMin = Aabb{}.min, boundsMax = Aabb{}.max;
};

struct MaterialData {
    glm::vec4 baseColorFactor{1.f};
    std::shared_ptr<const Image> baseColorTexture; // linear RGBA float, may be null
    // pbrMetallicRoughness factors, glTF's defaults when absent.
    float metallicFactor = 1.f;
    float roughnessFactor = 1.f;
    // The metallicRoughnessTexture (linear RGBA float: roughness in G, metalness in B), null
    // without one; it multiplies the factors texel by texel. A reflector that takes its
    // roughness from the material reads it per pixel (reflector_roughness.h).
    std::shared_ptr<const Image> metallicRoughnessTexture;
    // Its channels' means and its smallest roughness texel, 1 without one: the summaries for
    // whoever takes one figure per material (the material reflector rule, the effect plan's
    // sharpest lobe). Not weighted by how the mesh's UVs use the texels.
    float metallicTextureMean = 1.f;
    float roughnessTextureMean = 1.f;
    float roughnessTextureMin = 1.f;
    float metallic() const { return metallicFactor * metallicTextureMean; }
    float roughness() const { return roughnessFactor * roughnessTextureMean; }
    std::string name;
    bool doubleSided = false; // glTF: its back faces are surface too, not the inside of a solid
};

// One glTF primitive = one drawable: geometry plus its material.
struct Primitive {
    std::shared_ptr<const MeshData> mesh;
    std::shared_ptr<const MaterialData> material;
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
};

struct Camera {
    float yfov = 0.8f;  // radians
    float aspect = 0.f; // 0: take the viewport's
    float znear = 0.05f;
    float zfar = 200.f;
};

// The node's glTF `extras` as JSON text (empty when none). Parsed by whoever cares.
struct Extras {
    std::string json;
};

// Marks the root entity of each glTF node; `nodeIndex` is the index in the file.
struct SceneNode {
    int nodeIndex = -1;
};

} // namespace specula
