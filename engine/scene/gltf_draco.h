#pragma once
// Internal to the glTF loader: KHR_draco_mesh_compression, decoded with libdraco rather than
// tinygltf (see tinygltf_config.h for why).
#include "engine/scene/components.h"
#include "engine/scene/gltf_context.h"

#include <string>

namespace specula::gltf_internal {

struct DecodedAttributes {
    bool hasNormals = false;
    bool hasUvs = false;
};

// Decodes the payload `ext` (the primitive's extension object) and fills positions,
// normals, uvs and indices of `md`. Attributes the extension does not carry come from the
// primitive's ordinary accessors. `field` names the primitive.
DecodedAttributes decodeDraco(Context& ctx, const tinygltf::Primitive& prim,
                              const tinygltf::Value& ext, const std::string& field, MeshData& md);

} // namespace specula::gltf_internal
