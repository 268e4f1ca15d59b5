#pragma once
// Reads the Specula markup of a loaded glTF scene (node `extras`, docs/design.md §3):
//   "specula_probe": {...}           a probe at the node's world position (options inside)
//   "specula_reflector": true|{f0}   the node's meshes (and its subtree's) are mirrors
//   "specula_reflector": false       no mesh of the node's subtree is a mirror by its material
//   "specula_layer": "name"          groups the node's subtree with others of that name
// A scene without our markup still has mirrors: a node whose mesh has, on every primitive,
// a material with metallic >= ReflectorRule::minMetallic and roughness <=
// ReflectorRule::maxRoughness (0.9 and 0.1 by default; each factor times the mean of its
// channel in the metallic-roughness texture where there is one, MaterialData::metallic()
// and roughness()) is a reflector of its own, named after the node, with f0 = the Rec. 709
// luminance of the base colour factor (0.2126 R + 0.7152 G + 0.0722 B, clamped to [0, 1];
// of the primitives' mean when they differ) and its material's roughness, texel by texel
// where the material has a metallic-roughness texture (materialRoughness). The markup
// takes precedence: meshes claimed by a `true`/{f0} node stay in that node's reflector, and a
// `false` node's subtree gets no material reflector (an explicit `true` inside or above it still
// counts). Every other mesh is environment. Environment objects are the root nodes' subtrees (a
// single mesh-less root wrapping the whole scene is looked through), so each object can be
// its own probe layer.
#include "engine/ecs/registry.h"
#include "engine/math/aabb.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/mesh_bounds.h"

#include <string>
#include <unordered_set>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

namespace specula {

struct ProbeMarkup {
    std::string node;
    glm::vec3 position{0.f};
    nlohmann::json options; // the member object of "specula_probe"
};

struct ReflectorMarkup {
    std::string node;
    std::vector<ecs::Entity> meshes; // mesh entities of the node's subtree
    float f0 = -1.f;                 // < 0: perfect mirror
    // GGX roughness (alpha = roughness^2); 0 = a mirror. The markup's "roughness" (a number,
    // or "material": the material's, as for a reflector by material), else 0; a reflector by
    // material takes its material's (materialRoughness in reflector_roughness.h): the factor
    // and, per pixel, the metallic-roughness texture (`roughnessMap`, null when uniform).
    float roughness = 0.f;
    std::shared_ptr<const Image> roughnessMap;
};

struct EnvironmentObject {
    std::string name;
    std::vector<ecs::Entity> meshes;
    Aabb bounds; // world space, over every vertex
};

struct SceneMarkup {
    std::vector<ProbeMarkup> probes;
    std::vector<ReflectorMarkup> reflectors;
    std::vector<EnvironmentObject> objects;
    std::unordered_set<ecs::Entity> mirrorEntities;
};

// When a material alone makes its mesh a mirror (see above).
struct ReflectorRule {
    float minMetallic = 0.9f;
    float maxRoughness = 0.1f;
};

// Throws Error naming `file` and the node when markup has the wrong type.
SceneMarkup readSceneMarkup(ecs::Registry& registry, const LoadedScene& scene,
                            const std::string& file, const ReflectorRule& rule = {});

// Where the probe goes: the first `specula_probe` node, else the centre of the reflectors'
// bounds, else the centre of the scene.
glm::vec3 markupProbeCentre(const ecs::Registry& registry, const SceneMarkup& markup,
                            const LoadedScene& scene);
// Side of the cubic cell reflectors move in: the probe's `cell_size`, else 1.5 m.
float markupCellSize(const SceneMarkup& markup);
// How far from `centre` a reflector point can be: the farthest reflector vertex, and at
// least the corner of the cell.
float markupReflectorReach(const ecs::Registry& registry, const SceneMarkup& markup,
                           glm::vec3 centre, float cellSize);

} // namespace specula
