#pragma once
// Scenes built in code for the planner's tests and bench: each node() is one root node (one
// environment object unless its extras say otherwise), with a mesh or without.
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/transform_system.h"

#include <cmath>
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

// A closed box of half-extents `half` about the node's origin, faces looking out.
inline std::shared_ptr<MeshData> boxMesh(glm::vec3 half) {
    auto m = std::make_shared<MeshData>();
    for (int i = 0; i < 8; ++i)
        m->positions.push_back(glm::vec3((i & 1) ? half.x : -half.x, (i & 2) ? half.y : -half.y,
                                         (i & 4) ? half.z : -half.z));
    const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads)
        for (unsigned k : {q[0], q[1], q[2], q[0], q[2], q[3]})
            m->indices.push_back(k);
    m->boundsMin = -half;
    m->boundsMax = half;
    return m;
}

// A UV sphere of radius `r` (16 x 32 quads) about the node's origin.
inline std::shared_ptr<MeshData> sphereMesh(float r) {
    auto m = std::make_shared<MeshData>();
    const int n = 16;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= 2 * n; ++j) {
            const float th = 3.14159265f * float(i) / float(n);
            const float ph = 3.14159265f * float(j) / float(n);
            const glm::vec3 d(std::sin(th) * std::cos(ph), std::cos(th),
                              std::sin(th) * std::sin(ph));
            m->positions.push_back(r * d);
            m->normals.push_back(d);
        }
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < 2 * n; ++j) {
            const unsigned a = unsigned(i * (2 * n + 1) + j), b = a + unsigned(2 * n + 1);
            for (unsigned k : {a, b, a + 1, a + 1, b, b + 1})
                m->indices.push_back(k);
        }
    m->boundsMin = glm::vec3(-r);
    m->boundsMax = glm::vec3(r);
    return m;
}

} // namespace specula::test
