#include "gltf_material.h"

#include "engine/scene/gltf_accessors.h"
#include "engine/scene/texture_decode.h"

#include <algorithm>
#include <cmath>

namespace specula::gltf_internal {

// Images are decoded here, not by tinygltf: only the images a material uses, and only
// after the bufferView range they come from has been checked.
std::shared_ptr<const Image> MaterialCache::textureImage(int textureIndex, const std::string& from,
                                                         bool srgb) {
    const tinygltf::Model& m = ctx_.model();
    const auto& tex = ctx_.at(m.textures, textureIndex, "textures", from);
    const std::string tf = idx("textures", std::size_t(textureIndex));
    const int source = tex.source;
    const auto& img = ctx_.at(m.images, source, "images", tf + ".source");
    if (auto it = images_.find({source, srgb}); it != images_.end()) return it->second;
    const std::string imf = idx("images", std::size_t(source));
    Bytes bytes;
    if (img.bufferView >= 0) {
        bytes = viewBytes(ctx_, img.bufferView, imf);
    } else {
        bytes = {img.image.data(), img.image.size()};
        if (bytes.size == 0) ctx_.fail(imf + ".uri", "cannot read image '" + img.uri + "'");
    }
    std::string why;
    auto decoded = decodeTexture8(bytes.data, bytes.size, srgb, why);
    if (!decoded) ctx_.fail(imf, "undecodable image: " + why);
    auto ptr = std::make_shared<const Image>(std::move(*decoded));
    images_[{source, srgb}] = ptr;
    return ptr;
}

std::shared_ptr<const MaterialData> MaterialCache::material(int index, const std::string& from) {
    if (auto it = materials_.find(index); it != materials_.end()) return it->second;
    auto md = std::make_shared<MaterialData>();
    if (index < 0) {
        md->name = "default";
        materials_[index] = md;
        return md;
    }
    const auto& mat = ctx_.at(ctx_.model().materials, index, "materials", from);
    const std::string mf = idx("materials", std::size_t(index));
    md->name = mat.name;
    md->doubleSided = mat.doubleSided;
    const auto& f = mat.pbrMetallicRoughness.baseColorFactor;
    if (f.size() != 4)
        ctx_.fail(mf + ".pbrMetallicRoughness.baseColorFactor", "expected 4 numbers");
    for (int c = 0; c < 4; ++c) {
        if (!std::isfinite(f[std::size_t(c)]))
            ctx_.fail(mf + ".pbrMetallicRoughness.baseColorFactor", "non-finite value");
        md->baseColorFactor[c] = float(f[std::size_t(c)]);
    }
    const auto readFactor = [&](double v, const char* field) {
        const std::string where = mf + ".pbrMetallicRoughness." + field;
        if (!std::isfinite(v)) ctx_.fail(where, "non-finite value");
        // Out of range is against the spec but harmless: clamped, and said (a scene that
        // loaded before the factors were read still loads).
        if (v < 0.0 || v > 1.0) {
            ctx_.warn(where, std::to_string(v) + " is outside [0, 1]; clamped");
            v = std::clamp(v, 0.0, 1.0);
        }
        return float(v);
    };
    md->metallicFactor = readFactor(mat.pbrMetallicRoughness.metallicFactor, "metallicFactor");
    md->roughnessFactor = readFactor(mat.pbrMetallicRoughness.roughnessFactor, "roughnessFactor");
    const auto& bct = mat.pbrMetallicRoughness.baseColorTexture;
    if (bct.index >= 0) {
        if (bct.texCoord != 0)
            ctx_.warn(mf, "baseColorTexture uses TEXCOORD_" + std::to_string(bct.texCoord) +
                              "; only TEXCOORD_0 is loaded");
        md->baseColorTexture =
            textureImage(bct.index, mf + ".pbrMetallicRoughness.baseColorTexture", true);
    }
    const auto& mrt = mat.pbrMetallicRoughness.metallicRoughnessTexture;
    if (mrt.index >= 0) {
        const std::string where = mf + ".pbrMetallicRoughness.metallicRoughnessTexture";
        if (mrt.texCoord != 0)
            ctx_.warn(where, "uses TEXCOORD_" + std::to_string(mrt.texCoord) +
                                 "; only TEXCOORD_0 is loaded");
        const std::shared_ptr<const Image> mr = textureImage(mrt.index, where, false);
        // decodeTexture8 gives RGBA: roughness in G, metalness in B.
        double metallic = 0.0, roughness = 0.0;
        float roughnessMin = 1.f;
        const std::size_t texels = mr->pixels.size() / 4;
        if (texels == 0) ctx_.fail(where, "an empty image");
        for (std::size_t i = 0; i < texels; ++i) {
            roughness += double(mr->pixels[4 * i + 1]);
            metallic += double(mr->pixels[4 * i + 2]);
            roughnessMin = std::min(roughnessMin, mr->pixels[4 * i + 1]);
        }
        md->metallicRoughnessTexture = mr;
        md->roughnessTextureMean = float(std::clamp(roughness / double(texels), 0.0, 1.0));
        md->metallicTextureMean = float(std::clamp(metallic / double(texels), 0.0, 1.0));
        md->roughnessTextureMin = std::clamp(roughnessMin, 0.f, 1.f);
    }
    materials_[index] = md;
    return md;
}

} // namespace specula::gltf_internal
