// The glossy levels of a cooked distance probe (the composite's GGX chain,
// layer_00_ggx_<i>.ktx2): their content checks and reader (the writer:
// writer/distance_probe_writer.cpp). The manifest, the layers and the sky are
// distance_probe_asset.cpp's.
#include "distance_asset_internal.h"

#include "engine/core/error.h"
#include "engine/image/ktx2.h"

#include <algorithm>
#include <cmath>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula::distance_asset {

namespace {

// Face side of glossy level i (1 ..) of a probe of face_res n.
int glossyFaceRes(int n, std::size_t level) {
    return std::max(1, n >> std::min<std::size_t>(level, 30));
}

// "glossy.levels[k]": the manifest's entry for glossy level k + 1.
std::string glossyField(std::size_t k) {
    return "glossy.levels[" + std::to_string(k) + "]";
}

// Runs `check` on glossy level k + 1's image; an Error it throws names the level's field.
template <typename Check> void namedGlossy(std::size_t k, Check check) {
    try {
        check();
    } catch (const Error& e) {
        const std::string field = glossyField(k);
        if (e.field().rfind(field, 0) == 0) throw;
        throw Error(e.file(), e.field().empty() ? field : field + "." + e.field(), e.message());
    }
}

// Level 0's texels under texel x of a face of m texels over one of n: those it overlaps.
void footprintOf(int x, int m, int n, int& lo, int& hi) {
    lo = int((std::int64_t(x) * n) / m);
    hi = int(((std::int64_t(x) + 1) * n + m - 1) / m) - 1;
}

// The nearest distance of the composite under texel (x, y) of face f of a level of m texels
// a side (d_inf where it hits nothing there): what the level's A holds.
float nearestUnder(const std::array<Image, 6>& composite, int f, int x, int y, int m, float dInf) {
    const int n = composite[0].width;
    int x0, x1, y0, y1;
    footprintOf(x, m, n, x0, x1);
    footprintOf(y, m, n, y0, y1);
    float nearest = dInf;
    for (int sy = y0; sy <= y1; ++sy)
        for (int sx = x0; sx <= x1; ++sx)
            nearest = std::min(nearest, composite[std::size_t(f)].at(sx, sy)[3]);
    return nearest;
}

// A glossy level's A holds, per texel, the nearest finite distance of the composite under it:
// a level swapped with another probe's fails here.
void checkGlossyDistance(const std::array<Image, 6>& level, const std::array<Image, 6>& composite,
                         float dInf, const std::string& file) {
    const int m = level[0].width;
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < m; ++y)
            for (int x = 0; x < m; ++x) {
                const float nearest = nearestUnder(composite, f, x, y, m, dInf);
                const float d = level[std::size_t(f)].at(x, y)[3];
                if (d != nearest)
                    throw Error(file, "distance",
                                texelName(f, x, y) + " holds " + shortNumber(d) +
                                    " but the composite's nearest hit under it is " +
                                    shortNumber(nearest) +
                                    "; expected the min distance over its footprint (a level "
                                    "of another probe?)");
            }
}

// A compressed probe's glossy level: BC6H radiance (its blocks appended to a.glossyBlocks), A
// the nearest of the composite's distances under each texel, as an uncompressed level stores.
std::array<Image, 6> readCompressedGlossyLevel(const std::string& file, int n,
                                               DistanceProbeAsset& a) {
    Ktx2Texture t = readKtx2(file, {.width = n, .height = n, .faces = 6, .channels = 3});
    if (!t.bc6h)
        throw Error(file, "vkFormat",
                    "expected BC6H blocks: the manifest's compression is \"bc6h\"");
    const Image& rgb = t.levels[0];
    std::array<Image, 6> faces;
    for (int f = 0; f < 6; ++f) {
        faces[std::size_t(f)] = Image(n, n, 4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                float* p = faces[std::size_t(f)].at(x, y);
                const float* c = rgb.at(x, f * n + y);
                p[0] = c[0], p[1] = c[1], p[2] = c[2];
                p[3] = nearestUnder(a.layers[0].faces, f, x, y, n, a.dInf);
            }
    }
    a.glossyBlocks.push_back(std::move(t.blocks[0]));
    return faces;
}

} // namespace

void checkGlossy(const DistanceProbeAsset& a, const std::string& manifest,
                 const std::vector<std::string>& files) {
    if (a.glossyLevels.size() > std::size_t(kMaxGlossyLevels))
        throw Error(manifest, "glossy.levels",
                    "expected at most " + std::to_string(kMaxGlossyLevels) + " levels, got " +
                        std::to_string(a.glossyLevels.size()));
    for (std::size_t k = 0; k < a.glossyLevels.size(); ++k) {
        const std::array<Image, 6>& faces = a.glossyLevels[k];
        const int n = glossyFaceRes(a.faceRes, k + 1);
        namedGlossy(k, [&] {
            if (faces[0].width != n)
                throw Error(files[k], "size",
                            "expected faces of " + std::to_string(n) + " texels (level " +
                                std::to_string(k + 1) + " of face_res " +
                                std::to_string(a.faceRes) + "), got " +
                                std::to_string(faces[0].width));
            scanLayer(faces, a.dInf, faceSolidAngles(n), files[k]);
            checkGlossyDistance(faces, a.layers[0].faces, a.dInf, files[k]);
        });
    }
}

void readGlossyLevels(const ManifestFields& r, const json& glossy, const fs::path& dir,
                      DistanceProbeAsset& a, std::vector<std::string>& files) {
    if (!glossy.is_object()) throw Error(r.file, "glossy", "expected an object");
    const json& levels = r.member(glossy, "levels", "glossy.");
    if (!levels.is_array() || levels.empty() || levels.size() > std::size_t(kMaxGlossyLevels))
        throw Error(r.file, "glossy.levels",
                    "expected an array of 1 to " + std::to_string(kMaxGlossyLevels) + " levels");
    for (std::size_t k = 0; k < levels.size(); ++k) {
        const std::string path = glossyField(k) + ".";
        const json& j = levels[k];
        if (!j.is_object()) throw Error(r.file, glossyField(k), "expected an object");
        // Level k + 1 of L = levels.size(): perceptual roughness (k + 1) / L, as written.
        const double expected = double(k + 1) / double(levels.size());
        const double roughness = r.number(j, "roughness", path, 0.0, 1.0);
        if (std::fabs(roughness - expected) > 1e-6)
            throw Error(r.file, path + "roughness",
                        "says " + shortNumber(roughness) + "; level " + std::to_string(k + 1) +
                            " of " + std::to_string(levels.size()) + " has roughness " +
                            shortNumber(expected));
        const int n = glossyFaceRes(a.faceRes, k + 1);
        const ManifestFields::CheckedFile file = r.checkedFile(j, path, dir, maxLayerFileBytes(n));
        namedGlossy(k, [&] {
            if (a.compression == DistanceCompression::Bc6h) {
                a.glossyLevels.push_back(readCompressedGlossyLevel(file.path, n, a));
                return;
            }
            const Image stacked = readKtx2Cube(file.path, n);
            if (stacked.width != n || stacked.height != 6 * n || stacked.channels < 4)
                throw Error(file.path, "size",
                            "expected " + std::to_string(n) + " x " + std::to_string(6 * n) +
                                " RGBA, got " + std::to_string(stacked.width) + " x " +
                                std::to_string(stacked.height) + " with " +
                                std::to_string(stacked.channels) + " channels");
            a.glossyLevels.push_back(splitFaces(stacked));
        });
        files.push_back(file.path);
    }
}

} // namespace specula::distance_asset
