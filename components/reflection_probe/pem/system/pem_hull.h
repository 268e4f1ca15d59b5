#pragma once
// Which triangles of a reflector lie on its convex hull (Hakura et al. 2001, §4: "polygons on
// the convex hull use the distant layer only"). A triangle is on the hull when no vertex of the
// reflector's mesh lies in front of its plane (the counter-clockwise side, glTF's front)
// beyond a small tolerance scaled to the mesh: a ray leaving such a triangle on its front side
// heads into a half-space that holds none of the reflector, so it can never see the
// reflector again and the local layer has nothing to add. The cooker reads the flag of the
// triangle Embree hit (primitive, triangle), the runtime the same bits from a storage buffer by
// gl_PrimitiveID; both come from this one function.
#include "engine/scene/components.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace specula {

struct PemHullFlags {
    // Triangle k of primitive p is bit (firstTriangle[p] + k) of `bits` (32 to a word, low bit
    // first): triangles of every primitive in Mesh::primitives order, a primitive without
    // vertices counting none.
    std::vector<std::uint32_t> bits;
    std::vector<std::uint32_t> firstTriangle; // one per primitive
    std::size_t triangles = 0;
    std::size_t onHull = 0; // how many bits are set

    bool flag(std::size_t primitive, std::size_t triangle) const {
        const std::size_t k = std::size_t(firstTriangle[primitive]) + triangle;
        return (bits[k / 32] >> (k % 32)) & 1u;
    }
    // Every triangle on the hull: the reflector never sees itself (convex, flat).
    bool allOnHull() const { return onHull == triangles; }
};

// Positions in the mesh's own space: an affine transform keeps every vertex on its side of
// every plane, so the flags hold wherever the reflector is placed (a mirroring transform
// turns the front side with the winding, as Embree's geometric normal does). The tolerance is
// 1e-4 of the mesh's bounding-box diagonal: a flat mirror's own vertices lie on its plane.
// A triangle thinner than the tolerance (degenerate: its plane is rounding noise, as at a UV
// sphere's poles) counts as on the hull, so it cannot keep a convex reflector's local layer.
// O(triangles x distinct vertices).
PemHullFlags pemHullFlags(const Mesh& mesh);

} // namespace specula
