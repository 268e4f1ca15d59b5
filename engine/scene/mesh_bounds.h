#pragma once
// Bounds of meshes, local and through their entity's Transform::world.
#include "engine/ecs/registry.h"
#include "engine/math/aabb.h"
#include "engine/scene/components.h"

namespace specula {

// The mesh's local bounds: those its builder stored (the glTF loader always does), else,
// for a mesh built by hand without them, computed from its positions on each call.
Aabb localBounds(const MeshData& mesh);

// World bounds of an entity's Mesh over every vertex: tight, and linear in the vertex
// count, for the cooker's once-per-bake measurements. Empty without a Mesh or Transform.
Aabb meshWorldBounds(const ecs::Registry& registry, ecs::Entity e);

// World bounds of an entity's Mesh from the 8 corners of each primitive's local bounds:
// constant time per primitive, for per-frame checks. Conservative: it contains
// meshWorldBounds() and is wider under rotation. Empty without a Mesh or Transform.
Aabb meshWorldBoundsConservative(const ecs::Registry& registry, ecs::Entity e);

} // namespace specula
