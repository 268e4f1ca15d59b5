#pragma once
// Small procedural scenes for the ray-tracing tests, independent of the glTF loader.
#include "engine/ecs/registry.h"
#include "engine/scene/components.h"
#include "engine/scene/transform_system.h"

#include <cmath>
#include <memory>

#include <glm/gtc/constants.hpp>

namespace specula::testscenes {

inline void finishBounds(MeshData& m) {
    const Aabb b = Aabb::of(m.positions);
    m.boundsMin = b.min;
    m.boundsMax = b.max;
}

// Parallelogram corner, corner + u, corner + u + v, corner + v; front side along u x v;
// uv (0,0) at corner, (1,0) at corner + u.
inline std::shared_ptr<MeshData> quad(glm::vec3 corner, glm::vec3 u, glm::vec3 v) {
    auto m = std::make_shared<MeshData>();
    m->positions = {corner, corner + u, corner + u + v, corner + v};
    const glm::vec3 n = glm::normalize(glm::cross(u, v));
    m->normals = {n, n, n, n};
    m->uvs = {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}};
    m->indices = {0, 1, 2, 0, 2, 3};
    finishBounds(*m);
    return m;
}

// Axis-aligned cube [-0.5, 0.5]^3, outward faces, flat normals.
inline std::shared_ptr<MeshData> cube() {
    auto m = std::make_shared<MeshData>();
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = -1; sign <= 1; sign += 2) {
            glm::vec3 n(0.f);
            n[axis] = float(sign);
            glm::vec3 a(0.f), b(0.f);
            a[(axis + 1) % 3] = 1.f;
            b[(axis + 2) % 3] = 1.f;
            if (sign < 0) std::swap(a, b); // keep a x b pointing outwards
            const glm::vec3 c = 0.5f * n - 0.5f * a - 0.5f * b;
            const auto base = std::uint32_t(m->positions.size());
            m->positions.insert(m->positions.end(), {c, c + a, c + a + b, c + b});
            m->normals.insert(m->normals.end(), {n, n, n, n});
            m->indices.insert(m->indices.end(),
                              {base, base + 1, base + 2, base, base + 2, base + 3});
        }
    finishBounds(*m);
    return m;
}

// UV sphere with smooth normals.
inline std::shared_ptr<MeshData> sphere(float radius, int slices = 48, int stacks = 24) {
    auto m = std::make_shared<MeshData>();
    for (int i = 0; i <= stacks; ++i) {
        const float theta = glm::pi<float>() * float(i) / float(stacks);
        for (int j = 0; j <= slices; ++j) {
            const float phi = glm::two_pi<float>() * float(j) / float(slices);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi));
            m->positions.push_back(radius * n);
            m->normals.push_back(n);
            m->uvs.push_back({float(j) / float(slices), float(i) / float(stacks)});
        }
    }
    for (int i = 0; i < stacks; ++i)
        for (int j = 0; j < slices; ++j) {
            const auto a = std::uint32_t(i * (slices + 1) + j), b = a + std::uint32_t(slices + 1);
            m->indices.insert(m->indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    finishBounds(*m);
    return m;
}

inline ecs::Entity addMesh(ecs::Registry& reg, std::shared_ptr<MeshData> mesh,
                           glm::vec3 color = glm::vec3(1.f), Transform xf = {},
                           std::shared_ptr<const Image> texture = nullptr) {
    const ecs::Entity e = reg.create();
    auto material = std::make_shared<MaterialData>();
    material->baseColorFactor = glm::vec4(color, 1.f);
    material->baseColorTexture = std::move(texture);
    Mesh m;
    m.primitives.push_back(Primitive{std::move(mesh), std::move(material)});
    reg.emplace<Mesh>(e, std::move(m));
    reg.emplace<Transform>(e, xf);
    return e;
}

inline Image solidImage(int w, int h, glm::vec3 c) {
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            img.at(x, y)[0] = c.r;
            img.at(x, y)[1] = c.g;
            img.at(x, y)[2] = c.b;
        }
    return img;
}

inline bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace specula::testscenes
