#pragma once
// glTF 2.0 (.gltf and .glb, KHR_draco_mesh_compression) into ECS entities.
//
// Every node of the loaded scene becomes one entity with Name, Transform (local TRS, parent
// link, world already computed), SceneNode and, where the node has them, Mesh, Camera,
// NodeAnimation (the first animation's channels; Transform keeps the rest pose) and Extras.
// glTF meshes and materials used by several nodes are loaded once and shared through their
// shared_ptrs.
//
// Input is untrusted: every index, accessor range and decoded payload is checked, and any
// defect throws specula::Error with a one-line message "FILE: FIELD: what is wrong".
#include "engine/ecs/registry.h"

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

struct LoadedScene {
    std::vector<ecs::Entity> entities;        // one per node of the scene, parents before children
    std::vector<ecs::Entity> roots;           // the scene's root nodes
    glm::vec3 boundsMin{0.f}, boundsMax{0.f}; // world space, over all mesh instances
    std::vector<std::string> extensionsUsed;

    // Counting convention: each glTF mesh that some node of the scene uses is counted ONCE,
    // however many nodes instance it. `primitives` counts its triangle primitives,
    // `vertices` the vertices those primitives define (the POSITION accessor's count, after
    // Draco decoding) and `triangles` their index count / 3 (vertex count / 3 when
    // non-indexed). Primitives of other modes are skipped and reported in `warnings`.
    std::size_t meshes = 0, primitives = 0, vertices = 0, triangles = 0;
    std::size_t nodes = 0;     // entities created
    std::size_t materials = 0; // distinct materials the loaded primitives use

    // Things that were skipped but did not make the file unusable, one line each.
    std::vector<std::string> warnings;
};

// Loads the default scene of `path` (or the first, or every root node when the file
// has no scenes) into `registry`. Throws specula::Error; on error nothing is added to
// the registry.
LoadedScene loadGltf(const std::string& path, ecs::Registry& registry);

} // namespace specula
