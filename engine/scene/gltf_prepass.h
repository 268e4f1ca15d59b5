#pragma once
// Internal to the glTF loader: a pass over the JSON before tinygltf parses it.
#include "engine/scene/gltf_container.h"

#include <optional>
#include <string>

namespace specula::gltf_internal {

// Buffers are checked before tinygltf loads them, because tinygltf's message for a missing
// file neither names the buffer nor says it is a buffer.
//
// Draco primitives lose their `indices` in the JSON tinygltf sees: tinygltf insists that an
// indices accessor has a bufferView, which a Draco one has not, and the loader takes the
// indices from the Draco payload anyway. Returns the JSON to hand to tinygltf when it had
// to change, nullopt otherwise. `glb` is null for a .gltf file.
std::optional<std::string> precheck(const std::string& file, const std::string& jsonText,
                                    const GlbLayout* glb);

} // namespace specula::gltf_internal
