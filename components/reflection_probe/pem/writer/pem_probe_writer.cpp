#include "pem_probe_writer.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/pem/pem_asset_internal.h"
#include "components/reflection_probe/pem/pem_map_levels.h"
#include "components/reflection_probe/pem/writer/pem_compression.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/image/ktx2.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

using namespace pem_asset;

void writePemProbe(const PemAsset& asset, const std::string& dir, const std::string& sourceScene) {
    std::vector<std::string> files, localFiles;
    for (std::size_t k = 0; k < asset.samples.size(); ++k) {
        files.push_back((fs::path(dir) / sampleFileName(k)).string());
        localFiles.push_back((fs::path(dir) / localFileName(k)).string());
    }
    checkAsset(asset, (fs::path(dir) / "manifest.json").string(), files,
               (fs::path(dir) / kDistanceFile).string(), localFiles);
    checkPemBlocks(asset, files);
    const bool compressed = asset.compression == PemCompression::Bc6h;
    // A level of a sample's map as a cube: float RGB, or the sample's BC6H blocks of it.
    const auto writeLevel = [&](const std::string& path, const PemSampleMap& s, int level) {
        Ktx2Texture t{.cube = true, .bc6h = compressed, .levels = {pemStackLevel(s.map, level)}};
        if (compressed) t.blocks = {s.blocks.at(std::size_t(level))};
        writeKtx2(path, t);
    };

    writeProbeFolder(dir, sourceScene, [&](const fs::path& tmp) {
        json samples = json::array();
        for (std::size_t k = 0; k < asset.samples.size(); ++k) {
            throwIfCancelled(dir); // a signal between files wins; nothing is committed
            const std::string name = sampleFileName(k);
            const std::string path = (tmp / name).string();
            writeLevel(path, asset.samples[k], 0);
            json sample = {{"parameter", asset.samples[k].parameter},
                           {"file", name},
                           {"checksum", fileChecksum(path)}};
            for (int level = 1; level < asset.mipLevels; ++level) {
                const std::string mip = pemLevelFileName(k, level);
                const std::string mipPath = (tmp / mip).string();
                writeLevel(mipPath, asset.samples[k], level);
                sample["mips"].push_back({{"file", mip}, {"checksum", fileChecksum(mipPath)}});
            }
            if (asset.localLayer) {
                const std::string local = localFileName(k);
                const std::string localPath = (tmp / local).string();
                writeKtx2Cube(localPath, stackLocal(asset.samples[k].local));
                sample["local"] = {{"file", local}, {"checksum", fileChecksum(localPath)}};
            }
            samples.push_back(std::move(sample));
        }

        json manifest = probeManifestHeader("pem", sourceScene, asset.inputs, compressed);
        if (compressed) manifest["compression"] = "bc6h";
        manifest["geometry"] = asset.geometry;
        if (asset.localLayer)
            manifest["local_layer"] = {{"face_res", asset.localFaceRes},
                                       {"centre", vec3Json(asset.localSphere.centre)},
                                       {"radius", asset.localSphere.radius}};
        if (asset.mipLevels > 1) manifest["mip_levels"] = asset.mipLevels;
        if (asset.imageWidth > 0) manifest["image_size"] = {asset.imageWidth, asset.imageHeight};
        // Always written: "" says the bake traced a black sky, which a reader must not take for
        // a manifest that predates the field.
        manifest["sky_source"] = asset.skySource;
        if (const PemDistanceGeometry* g = asset.distance.get()) {
            const std::string path = (tmp / kDistanceFile).string();
            writeKtx2Cube(path, stackDistances(*g));
            manifest["distance"] = {{"face_res", g->faceRes},
                                    {"d_inf", g->dInf},
                                    {"range", g->range},
                                    {"tolerance", g->tolerance},
                                    {"max_steps", g->maxSteps},
                                    {"file", kDistanceFile},
                                    {"checksum", fileChecksum(path)}};
        }
        manifest.update(
            {{"centre", vec3Json(asset.centre)},
             {"parameter_kind", asset.parameterKind},
             {"path", asset.path},
             {"face_res", asset.faceRes},
             {"box", {{"min", vec3Json(asset.boxMin)}, {"max", vec3Json(asset.boxMax)}}},
             {"face_layout", compressed ? "KTX2 cube map per sample and MIP level (faceCount "
                                          "6, BC6H blocks), faces +X -X +Y -Y +Z -Z, RGB "
                                          "radiance"
                                        : "KTX2 cube map per sample (faceCount 6, float RGB), "
                                          "faces +X -X +Y -Y +Z -Z, RGB radiance"},
             {"samples", samples}});
        return manifest;
    });
}

} // namespace specula
