#include "pem_hull.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <glm/geometric.hpp>

namespace specula {

namespace {

// The triangle's three vertex indices: the index list, or consecutive vertices without one.
std::uint32_t vertexOf(const MeshData& m, std::size_t corner) {
    return m.indices.empty() ? std::uint32_t(corner) : m.indices[corner];
}

std::size_t triangleCount(const MeshData& m) {
    return (m.indices.empty() ? m.positions.size() : m.indices.size()) / 3;
}

} // namespace

PemHullFlags pemHullFlags(const Mesh& mesh) {
    PemHullFlags out;
    // Every vertex of the reflector, once per primitive: the hull is the whole mesh's.
    std::vector<glm::dvec3> points;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const Primitive& p : mesh.primitives) {
        out.firstTriangle.push_back(std::uint32_t(out.triangles));
        if (!p.mesh || p.mesh->positions.empty()) continue;
        out.triangles += triangleCount(*p.mesh);
        for (const glm::vec3& v : p.mesh->positions) {
            points.emplace_back(v);
            lo = glm::min(lo, glm::dvec3(v));
            hi = glm::max(hi, glm::dvec3(v));
        }
    }
    out.bits.assign((out.triangles + 31) / 32, 0u);
    if (points.empty()) return out;
    // Vertices split for normals or UVs are one point to the test (O(triangles x points)).
    std::sort(points.begin(), points.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
        return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
    });
    points.erase(std::unique(points.begin(), points.end()), points.end());
    const double eps = 1e-4 * glm::length(hi - lo);
    std::size_t k = 0;
    for (const Primitive& p : mesh.primitives) {
        if (!p.mesh || p.mesh->positions.empty()) continue;
        const MeshData& m = *p.mesh;
        for (std::size_t t = 0; t < triangleCount(m); ++t, ++k) {
            const glm::dvec3 a(m.positions[vertexOf(m, 3 * t)]);
            const glm::dvec3 b(m.positions[vertexOf(m, 3 * t + 1)]);
            const glm::dvec3 c(m.positions[vertexOf(m, 3 * t + 2)]);
            const glm::dvec3 n = glm::cross(b - a, c - a);
            const double len = glm::length(n);
            // Thinner than the tolerance (2 area / longest edge), the plane is noise: a pole
            // triangle of a UV sphere whose "coincident" vertices differ by float rounding.
            const double longest =
                std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
            bool hull = true;
            if (len > eps * longest) {
                const glm::dvec3 u = n / len;
                for (const glm::dvec3& q : points)
                    if (glm::dot(q - a, u) > eps) {
                        hull = false;
                        break;
                    }
            }
            if (hull) {
                out.bits[k / 32] |= 1u << (k % 32);
                ++out.onHull;
            }
        }
    }
    return out;
}

} // namespace specula
