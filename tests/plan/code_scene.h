#pragma once
// Scenes built in code for the planner's tests and bench: each node() is one root node (one
// environment object unless its extras say otherwise), with a mesh or without.
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/transform_system.h"

#include <memory>
#include <string>

namespace specula::test {

struct CodeScene {
    ecs::Registry reg;
    LoadedScene scene;
    std::shared_ptr<MaterialData> material = std::make_shared<MaterialData>();

    ecs::Entity node(const std::string& name, glm::vec3 at, std::shared_ptr<MeshData> mesh,
                     const std::string& extras = "", float scale = 1.f) {
        const ecs::Entity e = reg.create();
        reg.emplace<Name>(e, Name{name});
        Transform t;
        t.translation = at;
        t.scale = glm::vec3(scale);
        reg.emplace<Transform>(e, t);
        if (mesh) {
            Mesh m;
            m.name = name;
            m.primitives.push_back({mesh, material});
            reg.emplace<Mesh>(e, m);
        }
        if (!extras.empty()) reg.emplace<Extras>(e, Extras{extras});
        scene.entities.push_back(e);
        scene.roots.push_back(e);
        return e;
    }
};

} // namespace specula::test
