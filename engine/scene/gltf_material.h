#pragma once
// Internal to the glTF loader: materials and the base-colour images they use, each loaded
// once however many primitives share it.
#include "engine/scene/components.h"
#include "engine/scene/gltf_context.h"

#include <map>
#include <memory>
#include <string>

namespace specula::gltf_internal {

class MaterialCache {
public:
    explicit MaterialCache(Context& ctx) : ctx_(ctx) {}

    // Material `index` (-1: the glTF default material); `from` names the referring field.
    std::shared_ptr<const MaterialData> material(int index, const std::string& from);

private:
    std::shared_ptr<const Image> baseColorImage(int textureIndex, const std::string& from);

    Context& ctx_;
    std::map<int, std::shared_ptr<const MaterialData>> materials_;
    std::map<int, std::shared_ptr<const Image>> images_;
};

} // namespace specula::gltf_internal
