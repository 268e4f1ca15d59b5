#include "lightfield_asset.h"

#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "engine/image/bc1.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

const char* toString(LightFieldCompression c) {
    return c == LightFieldCompression::BC1 ? "bc1" : "none";
}

const char* slabName(int slab) {
    static const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    return slab >= 0 && slab < 6 ? names[slab] : "?";
}

std::size_t LightFieldAsset::layerBytes() const {
    const std::size_t n = std::size_t(atlasSize());
    return compression == LightFieldCompression::BC1 ? n * n / 2 : n * n * 3;
}

float disparityForDepth(const LightFieldAsset& a, float focalDepth) {
    if (!(focalDepth > 0.f) || std::isinf(focalDepth)) return 0.f;
    return a.cameraSpacing() / focalDepth * 0.5f * float(a.res);
}

void validateLightFieldSize(int cameras, int res, float cellSize, LightFieldCompression c,
                            const std::string& source) {
    if (cameras < 2 || cameras > 256)
        throw Error(source, "cameras",
                    "expected 2 to 256 cameras per side, got " + std::to_string(cameras));
    if (res < 4 || res > 4096 || res % 4 != 0)
        throw Error(source, "image_res",
                    "expected a multiple of 4 in [4, 4096] (BC1 blocks must not straddle two "
                    "cameras), got " +
                        std::to_string(res));
    if (cameras * res > 16384)
        throw Error(source, "cameras",
                    "NUM x RES = " + std::to_string(cameras * res) +
                        " exceeds the 16384 texel side of a 2D texture atlas");
    if (!(cellSize > 0.f) || !std::isfinite(cellSize))
        throw Error(source, "cell.size", "expected a positive size");
    (void)c;
}

// The figures of one slab against each other: what the bake derives from its depth
// histogram (near <= focal <= far, disparity from the focal depth, disjoint fractions).
void checkLightFieldSlabFigures(const LightFieldAsset& a, const LightFieldSlab& s,
                                const std::string& manifest, const std::string& path) {
    const auto fail = [&](const char* key, const std::string& why) {
        throw Error(manifest, path + key, why);
    };
    if (!(s.nearDepth <= s.farDepth))
        fail("depth_near", "exceeds depth_far (" + std::to_string(s.farDepth) + ")");
    if (!(s.minDepth <= s.maxDepth))
        fail("depth_min", "exceeds depth_max (" + std::to_string(s.maxDepth) + ")");
    const float slack = std::isfinite(s.focalDepth) ? 1e-5f * s.focalDepth : 0.f;
    if (!(s.focalDepth >= s.nearDepth - slack && s.focalDepth <= s.farDepth + slack))
        fail("focal_depth", "is not between depth_near and depth_far (it is their harmonic mean)");
    if (!(double(s.skyFraction) + double(s.intrudingFraction) <= 1.0 + 1e-6))
        fail("sky_fraction", "plus intruding_fraction exceeds 1");
    const float expected = disparityForDepth(a, s.focalDepth);
    if (!(std::fabs(s.disparity - expected) <= 1e-4f * expected + 1e-6f))
        fail("disparity_px", "is " + std::to_string(s.disparity) + ", the focal depth gives " +
                                 std::to_string(expected) +
                                 " (camera_spacing / focal_depth * RES / 2)");
}

LightFieldAsset readLightFieldProbe(const std::string& manifestPath) {
    return readLightFieldProbe(ParsedManifest::load(manifestPath).view());
}

LightFieldAsset readLightFieldProbe(const ProbeManifest& manifest) {
    const ManifestFields r{manifest.path};
    r.expectFlavour(manifest.json, "lightfield");
    const std::string& manifestPath = manifest.path;
    const json& m = manifest.json;
    const fs::path dir = fs::path(manifestPath).parent_path();

    LightFieldAsset a;
    const json& cell = r.member(m, "cell", "");
    a.cellCentre = r.vec3(cell, "centre", "cell.", kMaxCoordinate);
    a.cellSize = float(r.number(cell, "size", "cell.", 1e-4, 1e5));
    a.cameras = r.integer(m, "cameras", "", 2, 256);
    a.res = r.integer(m, "image_res", "", 4, 4096);
    const std::string comp = r.string(m, "compression", "");
    if (comp == "none")
        a.compression = LightFieldCompression::None;
    else if (comp == "bc1")
        a.compression = LightFieldCompression::BC1;
    else
        throw Error(manifestPath, "compression",
                    "expected \"none\" or \"bc1\", got \"" + comp + "\"");
    validateLightFieldSize(a.cameras, a.res, a.cellSize, a.compression, manifestPath);
    if (r.integer(m, "fov_deg", "", 1, 179) != 90)
        throw Error(manifestPath, "fov_deg", "expected 90 (the slab cameras' field of view)");
    const double spacing = r.number(m, "camera_spacing", "", 0.0, 1e6);
    if (std::fabs(spacing - a.cameraSpacing()) > 1e-5 * a.cameraSpacing())
        throw Error(manifestPath, "camera_spacing",
                    "expected 3 cell.size / (cameras - 1) = " + std::to_string(a.cameraSpacing()));
    const json& atlas = r.member(m, "atlas", "");
    const int n = a.atlasSize();
    if (r.integer(atlas, "width", "atlas.", 0, 16384) != n ||
        r.integer(atlas, "height", "atlas.", 0, 16384) != n)
        throw Error(manifestPath, "atlas",
                    "expected a " + std::to_string(n) + " x " + std::to_string(n) +
                        " atlas (cameras x image_res)");
    if (r.integer(atlas, "layers", "atlas.", 0, 256) != 6)
        throw Error(manifestPath, "atlas.layers", "expected 6 (one per slab)");
    a.depthPercentile = float(r.number(m, "depth_percentile", "", 0.0, 0.5));
    if (m.contains("bake"))
        a.bakeSeconds = r.number(r.member(m, "bake", ""), "seconds", "bake.", 0.0, 1e9);
    if (m.contains("intrusions")) {
        const json& list = m["intrusions"];
        if (!list.is_array()) throw Error(manifestPath, "intrusions", "expected an array");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string path = "intrusions[" + std::to_string(i) + "].";
            a.intrusions.push_back({r.string(list[i], "object", path),
                                    r.string(list[i], "region", path),
                                    float(r.number(list[i], "depth_m", path, -1e9, 1e9))});
        }
    }

    const json& slabs = r.member(m, "slabs", "");
    if (!slabs.is_array() || slabs.size() != 6)
        throw Error(manifestPath, "slabs", "expected an array of 6 slabs (+X -X +Y -Y +Z -Z)");
    for (int k = 0; k < 6; ++k) {
        const std::string path = "slabs[" + std::to_string(k) + "].";
        const json& j = slabs[std::size_t(k)];
        LightFieldSlab& s = a.slabs[std::size_t(k)];
        if (r.string(j, "slab", path) != slabName(k))
            throw Error(manifestPath, path + "slab",
                        std::string("expected \"") + slabName(k) + "\"");
        if (r.integer(j, "layer", path, 0, 5) != k)
            throw Error(manifestPath, path + "layer", "expected " + std::to_string(k));
        s.nearDepth = float(r.number(j, "depth_near", path, 0.0, 1e9, true));
        s.farDepth = float(r.number(j, "depth_far", path, 0.0, 1e9, true));
        s.minDepth = float(r.number(j, "depth_min", path, 0.0, 1e9));
        s.maxDepth = float(r.number(j, "depth_max", path, 0.0, 1e9));
        s.skyFraction = float(r.number(j, "sky_fraction", path, 0.0, 1.0));
        s.intrudingFraction = float(r.number(j, "intruding_fraction", path, 0.0, 1.0));
        s.focalDepth = float(r.number(j, "focal_depth", path, 0.0, 1e9, true));
        s.disparity = float(r.number(j, "disparity_px", path, 0.0, 1e6));
        checkLightFieldSlabFigures(a, s, manifestPath, path);
        if (std::uint64_t(r.number(j, "bytes", path, 0.0, 1e12)) != a.layerBytes())
            throw Error(manifestPath, path + "bytes",
                        "expected " + std::to_string(a.layerBytes()) + " (" + std::to_string(n) +
                            "^2 " + toString(a.compression) + ")");
        const std::string full = r.fileInFolder(j, path, dir);
        s.file = r.string(j, "file", path);
        // One read: the bytes are checksummed, size-checked and kept.
        s.data = r.namedFile(
            path, [&] { return readRegularFile<std::vector<std::uint8_t>>(full, a.layerBytes()); });
        s.checksum = r.checksum(j, path, bytesChecksum(s.data.data(), s.data.size()));
        if (s.data.size() != a.layerBytes())
            throw Error(full, "size",
                        "expected " + std::to_string(a.layerBytes()) + " bytes (" +
                            std::to_string(n) + "^2 " + toString(a.compression) + "), got " +
                            std::to_string(s.data.size()));
        if (a.compression == LightFieldCompression::BC1)
            if (const auto b = firstUndecodableBC1Block(s.data))
                throw Error(full, "texels",
                            "BC1 block " + std::to_string(*b) +
                                " is in the three-colour mode the baker never writes (its "
                                "index 3 decodes to transparent black)");
    }
    a.inputs = manifestProbeInputs(m, manifestPath);
    checkManifestSeal(manifest);
    return a;
}

} // namespace specula
