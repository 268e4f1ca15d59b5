#pragma once
// Internal to the glTF loader: a node's local transform and its camera.
#include "engine/scene/components.h"
#include "engine/scene/gltf_context.h"

#include <optional>
#include <string>

namespace specula::gltf_internal {

// Local TRS of a node; matrices are decomposed (shear cannot be represented and is
// reported). `nf` names the node.
Transform localTransform(Context& ctx, const tinygltf::Node& node, const std::string& nf);

// Camera `index`, or nullopt (with a warning) for a type this loader skips.
std::optional<Camera> camera(Context& ctx, int index, const std::string& from);

} // namespace specula::gltf_internal
