#include "pem_asset.h"
#include "pem_asset_internal.h"

#include "components/reflection_probe/pem/pem_map_levels.h"

#include "components/reflection_probe/distance/distance_probe_asset.h" // kMaxRadiance
#include "engine/core/error.h"
#include "engine/image/bc6h.h"
#include "engine/image/ktx2.h"

#include <nlohmann/json.hpp>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

namespace pem_asset {

constexpr int kMaxPemFaceRes = 4096;

// An N x 6N float RGB KTX2 is 72 N^2 bytes of pixels; header and offset tables fit the margin.
std::uint64_t maxSampleFileBytes(int n) {
    return 100ull * std::uint64_t(n) * std::uint64_t(n) + (1ull << 20);
}

std::string sampleFileName(std::size_t k) {
    char name[64];
    std::snprintf(name, sizeof name, "sample_%02zu.ktx2", k);
    return name;
}

std::string localFileName(std::size_t k) {
    char name[64];
    std::snprintf(name, sizeof name, "local_%02zu.ktx2", k);
    return name;
}

std::string samplePath(std::size_t k) {
    return "samples[" + std::to_string(k) + "].";
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

PemMap unstackMap(const Image& img, const PemAsset& a) {
    PemMap m{a.faceRes, a.boxMin, a.boxMax, {}, a.distance};
    m.texels.resize(std::size_t(PemMap::texelCount(a.faceRes)));
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            m.texels[std::size_t(y) * std::size_t(img.width) + std::size_t(x)] =
                glm::vec3(img.rgba(x, y));
    return m;
}

// A local map stacked as the distant ones, RGBA: premultiplied RGB and coverage.
Image stackLocal(const PemMap& m) {
    const int n = m.faceRes;
    Image out(n, 6 * n, 4);
    for (int t = 0; t < PemMap::texelCount(n); ++t) {
        for (int c = 0; c < 3; ++c)
            out.pixels[std::size_t(t) * 4 + std::size_t(c)] = m.texels[std::size_t(t)][c];
        out.pixels[std::size_t(t) * 4 + 3] = m.alpha[std::size_t(t)];
    }
    return out;
}

PemMap unstackLocal(const Image& img, const PemAsset& a) {
    PemMap m;
    m.faceRes = a.localFaceRes;
    m.local = a.localSphere;
    const std::size_t count = std::size_t(PemMap::texelCount(a.localFaceRes));
    m.texels.resize(count);
    m.alpha.resize(count);
    for (std::size_t t = 0; t < count; ++t) {
        const std::size_t p = t * std::size_t(img.channels);
        m.texels[t] = glm::vec3(img.pixels[p], img.pixels[p + 1], img.pixels[p + 2]);
        m.alpha[t] = img.pixels[p + 3];
    }
    return m;
}

// The distance cube's faces stacked as the maps' are, one channel.
Image stackDistances(const PemDistanceGeometry& g) {
    Image out(g.faceRes, 6 * g.faceRes, 1);
    for (std::size_t t = 0; t < g.distances.size(); ++t)
        out.pixels[t] = g.distances[t];
    return out;
}

// Both box, or both the same distance geometry (the same object, or equal contents).
bool sameGeometry(const PemDistanceGeometry* a, const PemDistanceGeometry* b) {
    return a == b || (a && b && *a == *b);
}

// Every texel's RGB finite in [0, kMaxRadiance]; the error names the face, texel and channel.
void checkRadiance(const PemMap& m, const std::string& file, std::size_t k) {
    static const char* faces[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    for (int level = 0; level < m.levels; ++level) {
        const int n = PemMap::levelRes(m.faceRes, level);
        const int offset = PemMap::levelOffset(m.faceRes, level);
        for (int t = 0; t < PemMap::texelCount(n); ++t)
            for (int c = 0; c < 3; ++c) {
                const float v = m.texels[std::size_t(offset + t)][c];
                if (v >= 0.f && v <= kMaxRadiance) continue; // false for NaN too
                throw Error(
                    level > 0 ? file + " (level " + std::to_string(level) + ")" : file, "radiance",
                    "sample " + std::to_string(k) + " face " + faces[t / (n * n)] + " texel (" +
                        std::to_string(t % n) + ", " + std::to_string(t / n % n) + ") channel " +
                        "RGB"[c] + " holds " + number(v) + "; expected a finite radiance in [0, " +
                        number(kMaxRadiance) + "]");
            }
    }
    for (std::size_t t = 0; t < m.alpha.size(); ++t) {
        const float v = m.alpha[t];
        if (v >= 0.f && v <= 1.f) continue; // false for NaN too
        throw Error(file, "alpha",
                    "sample " + std::to_string(k) + " texel " + std::to_string(t) + " holds " +
                        number(v) + "; expected a coverage in [0, 1]");
    }
}

// A compressed asset's sample holds one level of six faces' blocks per MIP level, an
// uncompressed one none. (That the blocks decode to the texels is the writer's check,
// checkPemBlocks; the reader makes the texels from them.)
void checkBlockCounts(const PemAsset& a, const PemSampleMap& s, const std::string& file,
                      std::size_t k) {
    const bool bc6h = a.compression == PemCompression::Bc6h;
    if (!bc6h && !s.blocks.empty())
        throw Error(file, "blocks",
                    "sample " + std::to_string(k) + " holds BC6H blocks in an uncompressed asset");
    if (!bc6h) return;
    if (s.blocks.size() != std::size_t(a.mipLevels))
        throw Error(file, "blocks",
                    "sample " + std::to_string(k) + " holds " + std::to_string(s.blocks.size()) +
                        " levels of BC6H blocks for " + std::to_string(a.mipLevels) +
                        " MIP level(s)");
    for (int level = 0; level < a.mipLevels; ++level) {
        const int n = PemMap::levelRes(a.faceRes, level);
        if (s.blocks[std::size_t(level)].size() != 6 * bc6hBytes(n, n))
            throw Error(file, "blocks",
                        "sample " + std::to_string(k) + " level " + std::to_string(level) +
                            " holds " + std::to_string(s.blocks[std::size_t(level)].size()) +
                            " bytes of BC6H, " + std::to_string(6 * bc6hBytes(n, n)) +
                            " expected for six faces of " + std::to_string(n));
    }
}

// The local layer's settings, and every sample's local map against them.
void checkLocal(const PemAsset& a, const std::string& manifest,
                const std::vector<std::string>& localFiles) {
    if (!a.localLayer) {
        for (std::size_t k = 0; k < a.samples.size(); ++k)
            if (a.samples[k].local.faceRes != 0)
                throw Error(manifest, samplePath(k) + "local",
                            "a local map in an asset without a local layer");
        return;
    }
    if (a.localFaceRes < 1 || a.localFaceRes > kMaxPemFaceRes)
        throw Error(manifest, "local_layer.face_res",
                    "expected an integer in [1, " + std::to_string(kMaxPemFaceRes) + "], got " +
                        std::to_string(a.localFaceRes));
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(a.localSphere.centre[i]) <= kMaxCoordinate))
            throw Error(manifest, "local_layer.centre", "expected a finite probe-local point");
    if (!(a.localSphere.radius > 0.f) || !std::isfinite(a.localSphere.radius))
        throw Error(manifest, "local_layer.radius",
                    "expected a finite radius > 0, got " + number(a.localSphere.radius));
    const std::size_t count = std::size_t(PemMap::texelCount(a.localFaceRes));
    for (std::size_t k = 0; k < a.samples.size(); ++k) {
        const PemMap& m = a.samples[k].local;
        if (m.faceRes != a.localFaceRes || m.local != a.localSphere || m.distance ||
            m.texels.size() != count || m.alpha.size() != count)
            throw Error(manifest, samplePath(k) + "local",
                        "expected " + std::to_string(count) + " RGBA texels of face resolution " +
                            std::to_string(a.localFaceRes) + " on the asset's local sphere");
        checkRadiance(m, localFiles[k], k);
    }
}

// What the reader checks of the whole asset; the writer runs it first too. `files[k]` names
// sample k's image, `distanceFile` the distance cube's.
void checkAsset(const PemAsset& a, const std::string& manifest,
                const std::vector<std::string>& files, const std::string& distanceFile,
                const std::vector<std::string>& localFiles) {
    for (int i = 0; i < 3; ++i)
        if (!(std::fabs(a.centre[i]) <= kMaxCoordinate))
            throw Error(manifest, "centre",
                        "coordinate " + number(a.centre[i]) + " is beyond " +
                            number(kMaxCoordinate) + " m (float precision)");
    if (a.parameterKind != "viewpoint" && a.parameterKind != "reflector")
        throw Error(manifest, "parameter_kind",
                    "expected \"viewpoint\" or \"reflector\", got \"" + a.parameterKind + "\"");
    if (a.path.empty() || a.path.size() > 64)
        throw Error(manifest, "path", "expected the name of a walk path (1 to 64 characters)");
    if (a.faceRes < 1 || a.faceRes > kMaxPemFaceRes)
        throw Error(manifest, "face_res",
                    "expected an integer in [1, " + std::to_string(kMaxPemFaceRes) + "], got " +
                        std::to_string(a.faceRes));
    const bool noImage = a.imageWidth == 0 && a.imageHeight == 0;
    if (!noImage &&
        (a.imageWidth < 1 || a.imageHeight < 1 || a.imageWidth > 8192 || a.imageHeight > 8192))
        throw Error(manifest, "image_size", "expected 1 to 8192 pixels on each side");
    for (int i = 0; i < 3; ++i)
        if (!(a.boxMin[i] < a.boxMax[i]) || !std::isfinite(a.boxMax[i] - a.boxMin[i]))
            throw Error(manifest, "box", "expected finite bounds with min < max on every axis");
    if (a.geometry != "box" && a.geometry != "distance")
        throw Error(manifest, "geometry",
                    "expected \"box\" or \"distance\", got \"" + a.geometry + "\"");
    if ((a.geometry == "distance") != bool(a.distance))
        throw Error(manifest, "geometry",
                    a.distance ? "a box-geometry asset holds a distance cube"
                               : "distance geometry without its distance cube");
    if (a.distance) checkPemDistanceGeometry(*a.distance, manifest, distanceFile);
    if (a.mipLevels < 1 || a.mipLevels > PemMap::maxLevels(a.faceRes))
        throw Error(manifest, "mip_levels",
                    "expected an integer in [1, " + std::to_string(PemMap::maxLevels(a.faceRes)) +
                        "] for faces of " + std::to_string(a.faceRes) + ", got " +
                        std::to_string(a.mipLevels));
    if (a.samples.empty() || a.samples.size() > std::size_t(kMaxPemSamples))
        throw Error(manifest, "samples",
                    "expected 1 to " + std::to_string(kMaxPemSamples) + " sample maps, got " +
                        std::to_string(a.samples.size()));
    for (std::size_t k = 0; k < a.samples.size(); ++k) {
        const PemSampleMap& s = a.samples[k];
        if (!(s.parameter >= 0.f && s.parameter <= 1.f))
            throw Error(manifest, samplePath(k) + "parameter",
                        "expected a number in [0, 1], got " + number(s.parameter));
        if (k > 0 && !(s.parameter > a.samples[k - 1].parameter))
            throw Error(manifest, samplePath(k) + "parameter",
                        "parameters must increase strictly: " + number(s.parameter) + " follows " +
                            number(a.samples[k - 1].parameter));
        const int texels = PemMap::texelCount(a.faceRes, a.mipLevels);
        if (s.map.faceRes != a.faceRes || s.map.boxMin != a.boxMin || s.map.boxMax != a.boxMax ||
            s.map.levels != a.mipLevels || s.map.texels.size() != std::size_t(texels) ||
            !sameGeometry(s.map.distance.get(), a.distance.get()))
            throw Error(manifest, samplePath(k) + "map",
                        "expected " + std::to_string(texels) + " texels of face resolution " +
                            std::to_string(a.faceRes) + " in " + std::to_string(a.mipLevels) +
                            " level(s) over the asset's box and geometry");
        checkRadiance(s.map, files[k], k);
        checkBlockCounts(a, s, files[k], k);
    }
    checkLocal(a, manifest, localFiles);
}

// One level of a sample's map, an N x 6N RGB cube (`n` a face's side), from `file`; a
// compressed asset's blocks are appended to `s.blocks`. A file stored otherwise than the
// manifest says (BC6H in an uncompressed asset, or float in a compressed one) names its vkFormat.
Image readMapLevel(const ManifestFields& r, const std::string& field,
                   const ManifestFields::CheckedFile& file, int n, const PemAsset& a,
                   PemSampleMap& s) {
    // The header must declare exactly N x 6N, checked before the pixels are allocated.
    Ktx2Texture t = r.namedFile(
        field, [&] { return readKtx2(file.path, {.width = n, .height = n, .faces = 6}); });
    const bool bc6h = a.compression == PemCompression::Bc6h;
    if (t.bc6h != bc6h)
        throw Error(file.path, "vkFormat",
                    bc6h ? "expected BC6H blocks: the manifest's compression is \"bc6h\""
                         : "expected float texels: the manifest states no compression");
    Image img = std::move(t.levels.at(0));
    if (img.channels < 3)
        throw Error(file.path, "channels",
                    "expected RGB, got " + std::to_string(img.channels) + " channel(s)");
    if (bc6h) s.blocks.push_back(std::move(t.blocks.at(0)));
    return img;
}

// Levels 1 .. levels-1 of a sample's map from its "mips" files, each exactly its size.
void readPemLevels(const ManifestFields& r, const json& sample, const std::string& path,
                   const fs::path& dir, const PemAsset& a, PemSampleMap& s) {
    const int levels = a.mipLevels;
    PemMap& map = s.map;
    map.levels = levels;
    if (levels <= 1) return;
    const json& mips = r.member(sample, "mips", path);
    if (!mips.is_array() || mips.size() != std::size_t(levels - 1))
        throw Error(r.file, path + "mips",
                    "expected an array of " + std::to_string(levels - 1) + " files (levels 1 to " +
                        std::to_string(levels - 1) + ")");
    for (int level = 1; level < levels; ++level) {
        const std::string field = path + "mips[" + std::to_string(level - 1) + "].";
        const int n = PemMap::levelRes(map.faceRes, level);
        const ManifestFields::CheckedFile file =
            r.checkedFile(mips[std::size_t(level - 1)], field, dir, maxSampleFileBytes(n));
        pemUnstackLevel(readMapLevel(r, field, file, n, a, s), level, map);
    }
}

} // namespace pem_asset

using namespace pem_asset;

PemAsset readPemProbe(const std::string& manifestPath) {
    return readPemProbe(ParsedManifest::load(manifestPath).view());
}

PemAsset readPemProbe(const ProbeManifest& manifest) {
    const ManifestFields r{manifest.path};
    const FormatVersion version = r.expectFlavour(manifest.json, "pem");
    const json& m = manifest.json;
    const fs::path dir = fs::path(manifest.path).parent_path();

    PemAsset a;
    a.manifestPath = manifest.path;
    if (m.contains("compression")) {
        if (r.string(m, "compression", "") != "bc6h")
            throw Error(manifest.path, "compression", "expected \"bc6h\" (or no member)");
        if (version.major < 3 || (version.major == 3 && version.minor < 2))
            throw Error(manifest.path, "compression",
                        "needs asset format 3.2 or newer; the manifest states " +
                            std::to_string(version.major) + "." + std::to_string(version.minor));
        a.compression = PemCompression::Bc6h;
    }
    a.centre = r.vec3(m, "centre", "", kMaxCoordinate);
    if (m.contains("sky_source")) a.skySource = r.string(m, "sky_source", "");
    a.parameterKind = r.string(m, "parameter_kind", "");
    a.path = r.string(m, "path", "");
    a.faceRes = r.integer(m, "face_res", "", 1, kMaxPemFaceRes);
    // Absent in manifests written before it was recorded.
    if (m.contains("image_size")) {
        const json& size = r.member(m, "image_size", "");
        if (!size.is_array() || size.size() != 2)
            throw Error(manifest.path, "image_size", "expected [width, height]");
        const json pair = {{"w", size[0]}, {"h", size[1]}};
        a.imageWidth = r.integer(pair, "w", "image_size.", 1, 8192);
        a.imageHeight = r.integer(pair, "h", "image_size.", 1, 8192);
    }
    const json& box = r.member(m, "box", "");
    a.boxMin = r.vec3(box, "min", "box.", FLT_MAX);
    a.boxMax = r.vec3(box, "max", "box.", FLT_MAX);
    // Absent in manifests written before distance geometry: those are box maps.
    if (m.contains("geometry")) a.geometry = r.string(m, "geometry", "");
    std::string distanceFile = (dir / kDistanceFile).string();
    if (a.geometry == "distance") {
        const json& d = r.member(m, "distance", "");
        auto g = std::make_shared<PemDistanceGeometry>();
        g->faceRes = r.integer(d, "face_res", "distance.", 1, kMaxPemFaceRes);
        g->dInf = float(r.number(d, "d_inf", "distance.", 0.0, FLT_MAX));
        g->range = float(r.number(d, "range", "distance.", 0.0, FLT_MAX));
        g->tolerance = float(r.number(d, "tolerance", "distance.", 0.0, FLT_MAX));
        g->maxSteps = r.integer(d, "max_steps", "distance.", 1, 40);
        const ManifestFields::CheckedFile file =
            r.checkedFile(d, "distance.", dir, maxSampleFileBytes(g->faceRes));
        a.distanceFile = file.name;
        a.distanceChecksum = file.checksum;
        distanceFile = file.path;
        const Image img =
            r.namedFile("distance.", [&] { return readKtx2Cube(file.path, g->faceRes); });
        g->distances.resize(std::size_t(PemMap::texelCount(g->faceRes)));
        for (std::size_t t = 0; t < g->distances.size(); ++t)
            g->distances[t] = img.pixels[t * std::size_t(img.channels)];
        a.distance = std::move(g);
    }
    // Absent in manifests written before local layers, and in assets without one.
    if (m.contains("local_layer")) {
        const json& l = r.member(m, "local_layer", "");
        a.localLayer = true;
        a.localFaceRes = r.integer(l, "face_res", "local_layer.", 1, kMaxPemFaceRes);
        a.localSphere.centre = r.vec3(l, "centre", "local_layer.", kMaxCoordinate);
        a.localSphere.radius = float(r.number(l, "radius", "local_layer.", 0.0, FLT_MAX));
    }
    // Absent in manifests written before MIP levels, and in single-level assets.
    if (m.contains("mip_levels"))
        a.mipLevels = r.integer(m, "mip_levels", "", 1, PemMap::maxLevels(a.faceRes));
    const json& samples = r.member(m, "samples", "");
    if (!samples.is_array() || samples.empty() || samples.size() > std::size_t(kMaxPemSamples))
        throw Error(manifest.path, "samples",
                    "expected an array of 1 to " + std::to_string(kMaxPemSamples) + " sample maps");
    std::vector<std::string> files, localFiles;
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const std::string path = samplePath(k);
        const json& j = samples[k];
        PemSampleMap s;
        s.parameter = float(r.number(j, "parameter", path, 0.0, 1.0));
        const ManifestFields::CheckedFile file =
            r.checkedFile(j, path, dir, maxSampleFileBytes(a.faceRes));
        s.file = file.name;
        s.checksum = file.checksum;
        s.map = unstackMap(readMapLevel(r, path, file, a.faceRes, a, s), a);
        readPemLevels(r, j, path, dir, a, s);
        if (a.localLayer) {
            const std::string localPath = path + "local.";
            const ManifestFields::CheckedFile local = r.checkedFile(
                r.member(j, "local", path), localPath, dir, maxSampleFileBytes(a.localFaceRes));
            s.localFile = local.name;
            s.localChecksum = local.checksum;
            const Image limg =
                r.namedFile(localPath, [&] { return readKtx2Cube(local.path, a.localFaceRes); });
            if (limg.channels < 4)
                throw Error(local.path, "channels",
                            "expected RGBA (premultiplied radiance, coverage), got " +
                                std::to_string(limg.channels) + " channel(s)");
            s.local = unstackLocal(limg, a);
            localFiles.push_back(local.path);
        } else {
            localFiles.push_back(file.path);
        }
        a.samples.push_back(std::move(s));
        files.push_back(file.path);
    }
    checkAsset(a, manifest.path, files, distanceFile, localFiles);
    a.inputs = manifestProbeInputs(manifest.json, manifest.path);
    checkManifestSeal(manifest);
    return a;
}

} // namespace specula
