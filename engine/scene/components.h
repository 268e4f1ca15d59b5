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
    // The metallicRoughnessTexture's means over its texels (metalness in B, roughness in G,
    // linear), 1 without one: the texture multiplies the factors texel by texel, and a
    // reflector takes one roughness, so the mean is what reaches it (readSceneMarkup). Not
    // weighted by how the mesh's UVs use the texels: a summary, not a per-pixel roughness.
    float metallicTextureMean = 1.f;
    float roughnessTextureMean = 1.f;
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
