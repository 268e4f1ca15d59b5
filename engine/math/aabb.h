#pragma once
// An axis-aligned box: the one bounds type of the engine, the cooker and the tools.
// Default-constructed it is empty (min above max on every axis), so a box grown point by
// point needs no "first point" special case. The empty limits are the largest finite
// floats, not infinities, so sums over an empty box (centre()) stay finite.
#include <algorithm>
#include <limits>
#include <span>

#include <glm/glm.hpp>

namespace specula {

struct Aabb {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};

    // The cube of half-side `half` around `centre`.
    static Aabb cube(glm::vec3 centre, float half) { return {centre - half, centre + half}; }
    static Aabb of(std::span<const glm::vec3> points) {
        Aabb b;
        for (const glm::vec3& p : points)
            b.extend(p);
        return b;
    }

    bool operator==(const Aabb&) const = default;

    bool empty() const { return min.x > max.x || min.y > max.y || min.z > max.z; }

    void extend(glm::vec3 p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    // Extending by an empty box changes nothing: its limits lose every min/max.
    void extend(const Aabb& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }

    // Meaningful for a non-empty box only.
    glm::vec3 centre() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; } // edge lengths, not half-lengths
    float boundingRadius() const { return 0.5f * glm::length(extent()); }

    // Closed box: points and boxes on the faces are inside, touching boxes overlap.
    bool contains(glm::vec3 p) const {
        return glm::all(glm::greaterThanEqual(p, min)) && glm::all(glm::lessThanEqual(p, max));
    }
    bool contains(const Aabb& b) const { return contains(b.min) && contains(b.max); }
    bool overlaps(const Aabb& b) const {
        return glm::all(glm::lessThanEqual(min, b.max)) && glm::all(glm::lessThanEqual(b.min, max));
    }

    Aabb translated(glm::vec3 d) const { return empty() ? *this : Aabb{min + d, max + d}; }
    // World bounds of a local box: the box around its 8 transformed corners. It contains the
    // transformed geometry but is not tight under rotation (up to sqrt(3) times wider).
    Aabb transformed(const glm::mat4& m) const {
        if (empty()) return {};
        Aabb out;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner((i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y,
                                   (i & 4) ? max.z : min.z);
            out.extend(glm::vec3(m * glm::vec4(corner, 1.f)));
        }
        return out;
    }

    // Euclidean distance from `p` to the box; 0 inside or on it.
    float distance(glm::vec3 p) const {
        return glm::length(glm::max(glm::vec3(0.f), glm::max(min - p, p - max)));
    }
    // How far this box reaches out of `outer` along any axis (> 0: by that much); <= 0: it
    // lies inside, with that much room to the nearest face.
    float overhang(const Aabb& outer) const {
        const glm::vec3 out = glm::max(max - outer.max, outer.min - min);
        return std::max({out.x, out.y, out.z});
    }
};

} // namespace specula
