#include "assetcooker/lib/inspect/inspect.h"

#include "engine/ecs/registry.h"
#include "engine/scene/gltf_loader.h"

namespace specula::cook {

nlohmann::json inspectScene(const std::string& path) {
    ecs::Registry registry;
    const LoadedScene scene = loadGltf(path, registry);
    auto vec3 = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
    nlohmann::json j;
    j["file"] = path;
    j["meshes"] = scene.meshes;
    j["primitives"] = scene.primitives;
    j["vertices"] = scene.vertices;
    j["triangles"] = scene.triangles;
    j["bounds"] = {{"min", vec3(scene.boundsMin)}, {"max", vec3(scene.boundsMax)}};
    j["extensionsUsed"] = scene.extensionsUsed;
    j["nodes"] = scene.nodes;
    j["materials"] = scene.materials;
    j["warnings"] = scene.warnings;
    return j;
}

} // namespace specula::cook
