#include "lightfield_probe_writer.h"

#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

namespace {

// JSON has no infinity: +inf depths are written as null.
json depthJson(float d) {
    return std::isinf(d) ? json(nullptr) : json(d);
}

void writeBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw Error(path.string(), "", "write failed");
}


} // namespace

void writeLightFieldProbe(const LightFieldAsset& a, const std::string& dir,
                          const std::string& sourceScene) {
    validateLightFieldSize(a.cameras, a.res, a.cellSize, a.compression, "");
    // The reader's checks, before anything is written: a probe its reader would refuse is
    // never written.
    const std::string manifest = (fs::path(dir) / "manifest.json").string();
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(a.cellCentre[i]) <= kMaxCoordinate))
            throw Error(manifest, "cell.centre",
                        "coordinate " + std::to_string(a.cellCentre[i]) + " is beyond " +
                            std::to_string(kMaxCoordinate) + " m (float precision)");
    for (int k = 0; k < 6; ++k) {
        const LightFieldSlab& s = a.slabs[std::size_t(k)];
        checkLightFieldSlabFigures(a, s, manifest, "slabs[" + std::to_string(k) + "].");
        if (a.compression == LightFieldCompression::BC1)
            if (const auto b = firstUndecodableBC1Block(s.data))
                throw Error(manifest, "slabs[" + std::to_string(k) + "]",
                            "BC1 block " + std::to_string(*b) + " is not decodable");
    }
    writeProbeFolder(dir, sourceScene, [&](const fs::path& tmp) {
        json slabs = json::array();
        for (int k = 0; k < 6; ++k) {
            throwIfCancelled(dir); // a signal between files wins; nothing is committed
            const LightFieldSlab& s = a.slabs[std::size_t(k)];
            if (s.data.size() != a.layerBytes())
                throw Error(dir, std::string("slab ") + slabName(k),
                            "atlas holds " + std::to_string(s.data.size()) + " bytes, expected " +
                                std::to_string(a.layerBytes()));
            const std::string name =
                std::string("slab_") + "xxyyzz"[k] + (k % 2 ? "neg" : "pos") +
                (a.compression == LightFieldCompression::BC1 ? ".bc1" : ".rgb8");
            writeBytes(tmp / name, s.data);
            slabs.push_back({{"slab", slabName(k)},
                             {"layer", k},
                             {"depth_near", depthJson(s.nearDepth)},
                             {"depth_far", depthJson(s.farDepth)},
                             {"depth_min", s.minDepth},
                             {"depth_max", s.maxDepth},
                             {"sky_fraction", s.skyFraction},
                             {"intruding_fraction", s.intrudingFraction},
                             {"focal_depth", depthJson(s.focalDepth)},
                             {"disparity_px", s.disparity},
                             {"bytes", s.data.size()},
                             {"file", name},
                             {"checksum", fileChecksum((tmp / name).string())}});
        }
        json intrusions = json::array();
        for (const LightFieldIntrusion& i : a.intrusions)
            intrusions.push_back(
                {{"object", i.object}, {"region", i.region}, {"depth_m", i.depth}});
        const int n = a.atlasSize();
        json manifest = probeManifestHeader("lightfield", sourceScene, a.inputs);
        manifest.update(
            {{"cell", {{"centre", vec3Json(a.cellCentre)}, {"size", a.cellSize}}},
             {"cameras", a.cameras},
             {"image_res", a.res},
             {"fov_deg", 90},
             {"camera_spacing", a.cameraSpacing()},
             {"compression", toString(a.compression)},
             {"depth_percentile", a.depthPercentile},
             {"atlas",
              {{"width", n},
               {"height", n},
               {"layers", 6},
               {"texel_format", a.compression == LightFieldCompression::BC1
                                    ? "BC1 (DXT1) blocks of sRGB colour, block rows top to bottom"
                                    : "sRGB-encoded RGB8, rows top to bottom"},
               {"layout", "layer k = slab +X -X +Y -Y +Z -Z; slab axes b = (a+1)%3, c = (a+2)%3; "
                          "camera (i, j) at s = (i/(NUM-1) - 1/2) 3l along b, t likewise along c, "
                          "tile texels [i RES, (i+1) RES) x [j RES, (j+1) RES); texel (x, y) "
                          "slope ((x+0.5) 2/RES - 1, (y+0.5) 2/RES - 1)"}}},
             {"focal_rule", "focal depth = harmonic mean of depth_near and depth_far (plenoptic "
                            "sampling); disparity_px = camera_spacing / focal_depth * RES / 2"},
             {"bake", {{"tracer", "embree"}, {"seconds", a.bakeSeconds}}},
             {"intrusions", intrusions},
             {"slabs", slabs}});
        return manifest;
    });
}

} // namespace specula
