#pragma once
// Internal to the glTF loader: the parsed model into entities.
#include "engine/ecs/registry.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/tinygltf_config.h"

#include <string>

namespace specula::gltf_internal {

// Checks the asset's version and required extensions, walks the scene's node hierarchy,
// converts every mesh, material and camera it reaches and fills `out`. Entities are created
// only after everything converted: on error the registry is unchanged.
void convertScene(const std::string& file, const tinygltf::Model& model, LoadedScene& out,
                  ecs::Registry& registry);

} // namespace specula::gltf_internal
