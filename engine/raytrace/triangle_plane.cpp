#include "triangle_plane.h"

#include "engine/scene/components.h"

#include <cmath>

namespace specula {

std::optional<Hit> hitOnTrianglePlane(const ecs::Registry& registry, const Hit& on,
                                      glm::vec3 origin, glm::vec3 dir) {
    const Transform* xf = registry.find<Transform>(on.entity);
    if (!xf || !on.primitive || !on.primitive->mesh) return std::nullopt;
    const MeshData& md = *on.primitive->mesh;
    const std::size_t first = std::size_t(on.triangle) * 3;
    if (first + 2 >= md.indices.size()) return std::nullopt;
    const std::uint32_t tri[3] = {md.indices[first], md.indices[first + 1], md.indices[first + 2]};
    for (const std::uint32_t i : tri)
        if (i >= md.positions.size()) return std::nullopt;
    // The same world-space vertices and normals EmbreeScene built the triangle from.
    const glm::mat3 linear(xf->world);
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k)
        p[k] = glm::vec3(xf->world * glm::vec4(md.positions[tri[k]], 1.f));
    const glm::vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const glm::vec3 cross = glm::cross(e1, e2);
    const float denom = glm::dot(dir, cross);
    const float area2 = glm::dot(cross, cross);
    if (!(area2 > 0.f) || !std::isfinite(area2) || !(std::fabs(denom) > 1e-12f * std::sqrt(area2)))
        return std::nullopt;

    Hit h = on;
    h.t = glm::dot(p[0] - origin, cross) / denom;
    h.position = origin + h.t * dir;
    // Barycentric weights of the plane point (u for vertex 1, v for vertex 2), unclamped.
    const glm::vec3 d = h.position - p[0];
    const float d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
    const float d20 = glm::dot(d, e1), d21 = glm::dot(d, e2);
    const float det = d00 * d11 - d01 * d01;
    const float u = (d11 * d20 - d01 * d21) / det, v = (d00 * d21 - d01 * d20) / det;
    const float w = 1.f - u - v;
    h.barycentric = {u, v};
    const bool mirrored = glm::determinant(linear) < 0.f;
    h.geometricNormal = (mirrored ? -cross : cross) / std::sqrt(area2);
    h.normal = h.geometricNormal;
    if (md.normals.size() == md.positions.size()) {
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
        const glm::vec3 n = w * (normalMatrix * md.normals[tri[0]]) +
                            u * (normalMatrix * md.normals[tri[1]]) +
                            v * (normalMatrix * md.normals[tri[2]]);
        const float len = glm::length(n);
        if (len > 1e-12f && std::isfinite(len)) h.normal = n / len;
    }
    return h;
}

} // namespace specula
