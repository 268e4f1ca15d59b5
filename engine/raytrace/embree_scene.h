#pragma once
// An Embree BVH over the meshes of a registry, in world space, with the surface attributes
// the tracer needs (normal, uv, albedo) at each hit.
#include "engine/ecs/registry.h"
#include "engine/scene/components.h"

#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace specula {

struct Hit {
    float t = 0.f;           // along the ray, in units of |dir|
    glm::vec3 position{0.f}; // world space
    ecs::Entity entity = ecs::kNullEntity;
    const Primitive* primitive = nullptr; // owned by the EmbreeScene, valid while it lives
    std::size_t primitiveIndex = 0;       // index in the entity's Mesh::primitives
    unsigned triangle = 0;
    glm::vec2 barycentric{0.f};               // (u, v): weights of vertices 1 and 2
    glm::vec3 geometricNormal{0.f, 1.f, 0.f}; // unit, counter-clockwise front (glTF)
    glm::vec3 normal{0.f, 1.f, 0.f};          // unit interpolated normal, geometric when unusable
    glm::vec2 uv{0.f};                        // zero when the mesh has none
    glm::vec3 albedo{1.f};                    // baseColorFactor.rgb x texture(uv).rgb
};

class EmbreeScene {
public:
    using Filter = std::function<bool(ecs::Entity)>;

    // Every entity with Mesh and Transform (and accepted by `include`, when given), in world
    // space through Transform::world: run updateWorldTransforms first. Throws Error when
    // Embree fails.
    explicit EmbreeScene(ecs::Registry& registry, const Filter& include = {});
    ~EmbreeScene();
    EmbreeScene(EmbreeScene&&) noexcept;
    EmbreeScene& operator=(EmbreeScene&&) noexcept;
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Closest hit in (tnear, tfar). `accept`: hits on entities it rejects are passed
    // through. Thread-safe.
    std::optional<Hit> intersect(glm::vec3 origin, glm::vec3 dir, float tnear = 1e-4f,
                                 float tfar = std::numeric_limits<float>::infinity(),
                                 const Filter* accept = nullptr) const;

    std::size_t geometryCount() const;
    bool empty() const { return geometryCount() == 0; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace specula
