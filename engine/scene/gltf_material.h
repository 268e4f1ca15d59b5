#pragma once
// Internal to the glTF loader: materials and the images they use, each loaded
// once however many primitives share it.
#include "engine/scene/components.h"
#include "engine/scene/gltf_context.h"

#include <map>
#include <memory>
#include <string>
#include <utility>

namespace specula::gltf_internal {

class MaterialCache {
public:
    explicit MaterialCache(Context& ctx) : ctx_(ctx) {}

    // Material `index` (-1: the glTF default material); `from` names the referring field.
    std::shared_ptr<const MaterialData> material(int index, const std::string& from);

private:
    // The image of texture `textureIndex`, decoded from sRGB (colour) or as stored (data).
    std::shared_ptr<const Image> textureImage(int textureIndex, const std::string& from, bool srgb);

    Context& ctx_;
    std::map<int, std::shared_ptr<const MaterialData>> materials_;
    std::map<std::pair<int, bool>, std::shared_ptr<const Image>> images_; // (source, srgb)
};

} // namespace specula::gltf_internal
