#include "distance_probe_writer.h"

#include "components/reflection_probe/distance/distance_asset_internal.h"
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/image/ktx2.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

using namespace distance_asset;

namespace {

std::string layerFileName(std::size_t i) {
    char name[64];
    std::snprintf(name, sizeof name, "layer_%02zu.ktx2", i);
    return name;
}

// Glossy level i (1 ..): the composite's (layer 0's) chain.
std::string glossyFileName(std::size_t i) {
    return "layer_00_ggx_" + std::to_string(i) + ".ktx2";
}

// Where each glossy level's image goes in `dir`: [k] is level k + 1's.
std::vector<std::string> glossyFilePaths(const DistanceProbeAsset& asset, const std::string& dir) {
    std::vector<std::string> glossyFiles;
    for (std::size_t k = 0; k < asset.glossyLevels.size(); ++k)
        glossyFiles.push_back((fs::path(dir) / glossyFileName(k + 1)).string());
    return glossyFiles;
}

// Writes `faces`' RGB as the BC6H cube `blocks` encode (six faces in order) to `path`.
void writeBc6hCube(const std::string& path, const std::array<Image, 6>& faces,
                   const std::vector<std::uint8_t>& blocks) {
    writeKtx2(
        path,
        Ktx2Texture{.cube = true, .bc6h = true, .levels = {stackFaces(faces)}, .blocks = {blocks}});
}

// Writes each glossy level's image into `tmp` (throwIfCancelled(dir) before each) and returns
// the manifest's "glossy" member. Only for an asset with glossy levels.
json writeGlossyLevels(const DistanceProbeAsset& asset, const fs::path& tmp,
                       const std::string& dir) {
    const std::size_t count = asset.glossyLevels.size();
    json levels = json::array();
    for (std::size_t k = 0; k < count; ++k) {
        throwIfCancelled(dir);
        const std::string name = glossyFileName(k + 1);
        const std::string path = (tmp / name).string();
        if (asset.compression == DistanceCompression::Bc6h)
            writeBc6hCube(path, asset.glossyLevels[k], asset.glossyBlocks.at(k));
        else
            writeKtx2Cube(path, stackFaces(asset.glossyLevels[k]));
        levels.push_back({{"file", name},
                          {"checksum", fileChecksum(path)},
                          {"roughness", double(k + 1) / double(count)}});
    }
    return {{"levels", levels}};
}

std::string distanceFileName(const std::string& radianceName) {
    const std::string stem = radianceName.substr(0, radianceName.rfind('.'));
    return stem + "_distance.ktx2";
}

// The composite's distances (A) as a one-channel N x 6N image, faces stacked.
Image stackedDistance(const std::array<Image, 6>& faces) {
    const int n = faces[0].width;
    Image out(n, 6 * n, 1);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x)
                out.at(x, f * n + y)[0] = faces[std::size_t(f)].at(x, y)[3];
    return out;
}

// Writes the composite's BC6H radiance as `name` in `tmp` and its distance beside it
// (name_distance.ktx2); returns the layer's "file", "checksum" and "distance" members.
json writeCompressedComposite(const DistanceProbeAsset& a, const fs::path& tmp,
                              const std::string& name) {
    const DistanceProbeLayer& composite = a.layers.at(0);
    const std::string radiance = (tmp / name).string();
    writeBc6hCube(radiance, composite.faces, a.compositeBlocks);
    const std::string distanceName = distanceFileName(name);
    const std::string distance = (tmp / distanceName).string();
    writeKtx2(distance, Ktx2Texture{.cube = true,
                                    .halfFloat = a.halfCompositeDistance,
                                    .levels = {stackedDistance(composite.faces)}});
    return {{"file", name},
            {"checksum", fileChecksum(radiance)},
            {"distance", {{"file", distanceName}, {"checksum", fileChecksum(distance)}}}};
}

} // namespace

void writeDistanceProbe(const DistanceProbeAsset& baked, const std::string& dir,
                        const std::string& sourceScene) {
    // The object layers go to disk as RGBA16F when they fit: the runtime rounds them to half
    // for the GPU anyway (storedDistanceAsset), so the file loses nothing the runtime uses
    // and takes half the bytes. Their figures are restated from the rounded texels, as the
    // reader measures them. The composite stays float32, as the GPU holds it.
    const bool halfObjectLayers = objectLayersFitHalf(baked);
    DistanceProbeAsset rounded;
    if (halfObjectLayers) {
        rounded = baked;
        roundObjectLayersToHalf(rounded);
        for (std::size_t i = 1; i < rounded.layers.size(); ++i) {
            DistanceProbeLayer& L = rounded.layers[i];
            const DistanceLayerContent c = measureDistanceLayer(
                L.faces, rounded.dInf, (fs::path(dir) / layerFileName(i)).string());
            L.minDistance = c.minDistance;
            L.maxDistance = c.maxDistance;
            L.solidAngle = float(c.solidAngle);
            if (c.solidAngle > 0.0)
                L.avgDistance = std::clamp(L.avgDistance, c.minDistance, c.maxDistance);
        }
    }
    const DistanceProbeAsset& asset = halfObjectLayers ? rounded : baked;
    // The reader's checks, before anything is written: a probe its reader would refuse is
    // never written (errors name the files as they would be).
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(asset.centre[i]) <= kMaxCoordinate))
            throw Error(dir, "centre",
                        "coordinate " + shortNumber(asset.centre[i]) + " is beyond " +
                            shortNumber(kMaxCoordinate) + " m (float precision)");
    std::vector<std::string> files;
    for (std::size_t i = 0; i < asset.layers.size(); ++i)
        files.push_back((fs::path(dir) / layerFileName(i)).string());
    checkContent(asset, (fs::path(dir) / "manifest.json").string(), files,
                 glossyFilePaths(asset, dir), (fs::path(dir) / "sky.ktx2").string());
    const bool compressed = asset.compression == DistanceCompression::Bc6h;
    if (compressed) checkCompressedComposite(asset, files[0], glossyFilePaths(asset, dir));

    writeProbeFolder(dir, sourceScene, [&](const fs::path& tmp) {
        json layers = json::array();
        for (std::size_t i = 0; i < asset.layers.size(); ++i) {
            throwIfCancelled(dir); // a signal between files wins; nothing is committed
            const DistanceProbeLayer& L = asset.layers[i];
            const std::string name = layerFileName(i);
            json stored;
            if (i == 0 && compressed) {
                stored = writeCompressedComposite(asset, tmp, name);
            } else {
                const std::string path = (tmp / name).string();
                writeKtx2(path, Ktx2Texture{.cube = true,
                                            .halfFloat = i > 0 && halfObjectLayers,
                                            .levels = {stackFaces(L.faces)}});
                stored = {{"file", name}, {"checksum", fileChecksum(path)}};
            }
            json layer = {{"name", L.name},
                          {"order", i},
                          {"objects", L.objects},
                          {"avg_distance", L.avgDistance},
                          {"min_distance", L.minDistance},
                          {"max_distance", L.maxDistance},
                          {"solid_angle_sr", L.solidAngle},
                          {"box_min", vec3Json(L.boxMin)},
                          {"box_max", vec3Json(L.boxMax)},
                          {"method", L.method}};
            layer.update(stored);
            layers.push_back(std::move(layer));
        }
        json manifest = probeManifestHeader("distance", sourceScene, asset.inputs, compressed);
        if (compressed) manifest["compression"] = "bc6h";
        manifest.update(
            {{"centre", vec3Json(asset.centre)},
             {"range_D", asset.range},
             {"d_inf", asset.dInf},
             {"face_res", asset.faceRes},
             {"box", {{"min", vec3Json(asset.boxMin)}, {"max", vec3Json(asset.boxMax)}}},
             {"face_layout", compressed ? "KTX2 cube maps (faceCount 6), faces +X -X +Y -Y +Z "
                                          "-Z: the composite's radiance BC6H, its distance "
                                          "from the centre R16F or R32F beside it; object "
                                          "layers RGBA (half floats where they fit)"
                                        : "KTX2 cube map (faceCount 6, RGBA: float32 for the "
                                          "composite, half floats for object layers that fit), "
                                          "faces +X -X +Y -Y +Z -Z, RGB radiance, A distance "
                                          "from the centre"},
             {"layers", layers}});
        if (!asset.effectPlan.empty()) manifest["effect_plan"] = json::parse(asset.effectPlan);
        if (!asset.glossyLevels.empty()) manifest["glossy"] = writeGlossyLevels(asset, tmp, dir);
        if (!asset.sky.empty()) {
            const std::string path = (tmp / "sky.ktx2").string();
            writeKtx2Image(path, asset.sky);
            manifest["sky"] = {{"file", "sky.ktx2"}, {"checksum", fileChecksum(path)}};
        }
        return manifest;
    });
}

} // namespace specula
