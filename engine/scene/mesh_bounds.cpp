#include "mesh_bounds.h"

namespace specula {

namespace {

// The union of primitiveBounds(mesh data, world matrix) over the primitives of e's Mesh.
template <class F>
Aabb overPrimitives(const ecs::Registry& registry, ecs::Entity e, F primitiveBounds) {
    Aabb box;
    const Mesh* mesh = registry.find<Mesh>(e);
    const Transform* t = registry.find<Transform>(e);
    if (!mesh || !t) return box;
    for (const Primitive& p : mesh->primitives)
        box.extend(primitiveBounds(*p.mesh, t->world));
    return box;
}

} // namespace

Aabb localBounds(const MeshData& mesh) {
    const Aabb stored{mesh.boundsMin, mesh.boundsMax};
    return stored.empty() ? Aabb::of(mesh.positions) : stored;
}

Aabb meshWorldBounds(const ecs::Registry& registry, ecs::Entity e) {
    return overPrimitives(registry, e, [](const MeshData& m, const glm::mat4& world) {
        Aabb box;
        for (const glm::vec3& v : m.positions)
            box.extend(glm::vec3(world * glm::vec4(v, 1.f)));
        return box;
    });
}

Aabb meshWorldBoundsConservative(const ecs::Registry& registry, ecs::Entity e) {
    return overPrimitives(registry, e, [](const MeshData& m, const glm::mat4& world) {
        return localBounds(m).transformed(world);
    });
}

} // namespace specula
