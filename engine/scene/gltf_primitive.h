#pragma once
// Internal to the glTF loader: one triangle primitive into MeshData, checked and repaired.
#include "engine/scene/components.h"
#include "engine/scene/gltf_context.h"

#include <memory>
#include <string>

namespace specula::gltf_internal {

// Geometry of a TRIANGLES primitive (plain accessors or Draco): positions finite, indices
// in range and a multiple of 3, unit normals everywhere (generated where missing or
// unusable), uvs finite or absent, bounds set. `field` names the primitive.
std::shared_ptr<const MeshData> buildPrimitive(Context& ctx, const tinygltf::Primitive& prim,
                                               const std::string& field);

} // namespace specula::gltf_internal
