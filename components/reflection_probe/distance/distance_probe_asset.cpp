#include "distance_probe_asset.h"
#include "distance_asset_internal.h"

#include "components/reflection_probe/manifest_fields.h"

#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "engine/image/ktx2.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

using namespace distance_asset;

namespace {
constexpr std::uint64_t kMaxSkyFileBytes = 4ull << 30;
} // namespace

double cubeTexelSolidAngle(int x, int y, int n) {
    // The integral of dA cos / r^2 over the texel: signed sum of the corner function
    // atan(st / sqrt(s^2 + t^2 + 1)) at the texel's four corners (s, t in [-1, 1]).
    auto corner = [n](int i, int j) {
        const double s = 2.0 * i / n - 1.0, t = 2.0 * j / n - 1.0;
        return std::atan2(s * t, std::sqrt(s * s + t * t + 1.0));
    };
    return corner(x + 1, y + 1) - corner(x, y + 1) - corner(x + 1, y) + corner(x, y);
}

// --- shared with the glossy levels (distance_asset_internal.h) ------------------------------

namespace distance_asset {

std::uint64_t maxLayerFileBytes(int n) {
    return 100ull * std::uint64_t(n) * std::uint64_t(n) + (1ull << 20);
}

Image stackFaces(const std::array<Image, 6>& faces) {
    const int n = faces[0].width;
    Image out(n, 6 * n, 4);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec4 v = faces[f].rgba(x, y);
                float* p = out.at(x, f * n + y);
                p[0] = v.r, p[1] = v.g, p[2] = v.b, p[3] = v.a;
            }
    return out;
}

std::array<Image, 6> splitFaces(const Image& stacked) {
    const int n = stacked.width;
    std::array<Image, 6> faces;
    for (int f = 0; f < 6; ++f) {
        faces[f] = Image(n, n, 4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec4 v = stacked.rgba(x, f * n + y);
                float* p = faces[f].at(x, y);
                p[0] = v.r, p[1] = v.g, p[2] = v.b, p[3] = v.a;
            }
    }
    return faces;
}

std::string texelName(int face, int x, int y) {
    static const char* names[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    return std::string("face ") + names[face] + " texel (" + std::to_string(x) + ", " +
           std::to_string(y) + ")";
}

std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

std::vector<float> faceSolidAngles(int n) {
    std::vector<float> out(std::size_t(n) * std::size_t(n));
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
            out[std::size_t(y) * std::size_t(n) + std::size_t(x)] =
                float(cubeTexelSolidAngle(x, y, n));
    return out;
}

DistanceLayerContent scanLayer(const std::array<Image, 6>& faces, float dInf,
                               const std::vector<float>& solidAngles, const std::string& file) {
    const int n = faces[0].width;
    DistanceLayerContent c;
    float lo = FLT_MAX, hi = 0.f;
    for (int f = 0; f < 6; ++f) {
        const Image& img = faces[std::size_t(f)];
        if (img.width != n || img.height != n || img.channels != 4 ||
            img.pixels.size() != std::size_t(n) * std::size_t(n) * 4)
            throw Error(file, "size",
                        "face " + std::to_string(f) + " is not " + std::to_string(n) + " x " +
                            std::to_string(n) + " RGBA");
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float* p = img.at(x, y);
                if (!radianceOk(p)) refuseRadiance(p, file, texelName(f, x, y));
                const float d = p[3];
                if (!(d > 0.f && d <= dInf))
                    throw Error(file, "distance",
                                texelName(f, x, y) + " holds " + shortNumber(d) +
                                    "; expected a distance in (0, d_inf = " + shortNumber(dInf) +
                                    "]");
                if (d == dInf) continue; // sees nothing
                lo = std::min(lo, d);
                hi = std::max(hi, d);
                c.solidAngle += solidAngles[std::size_t(y) * std::size_t(n) + std::size_t(x)];
            }
    }
    c.minDistance = c.solidAngle > 0.0 ? lo : 0.f;
    c.maxDistance = hi;
    return c;
}

} // namespace distance_asset

DistanceLayerContent measureDistanceLayer(const std::array<Image, 6>& faces, float dInf,
                                          const std::string& file) {
    return scanLayer(faces, dInf, faceSolidAngles(faces[0].width), file);
}

DistanceProbeAsset readDistanceProbe(const std::string& manifestPath) {
    return readDistanceProbe(ParsedManifest::load(manifestPath).view());
}

DistanceProbeAsset readDistanceProbe(const ProbeManifest& manifest) {
    const ManifestFields r{manifest.path};
    const FormatVersion version = r.expectFlavour(manifest.json, "distance");
    const std::string& manifestPath = manifest.path;
    const json& m = manifest.json;
    const fs::path dir = fs::path(manifestPath).parent_path();
    bool compressed = false;
    if (m.contains("compression")) {
        if (r.string(m, "compression", "") != "bc6h")
            throw Error(manifestPath, "compression", "expected \"bc6h\" (or no member)");
        if (version.major < 3)
            throw Error(manifestPath, "compression",
                        "needs asset format 3.0 or newer; the manifest states " +
                            std::to_string(version.major) + "." + std::to_string(version.minor));
        compressed = true;
    }

    DistanceProbeAsset a;
    a.manifestPath = manifestPath;
    a.centre = r.vec3(m, "centre", "", kMaxCoordinate);
    a.range = float(r.number(m, "range_D", "", 1e-6, 1e7));
    a.dInf = float(r.number(m, "d_inf", "", 1e-6, 1e9));
    a.faceRes = r.integer(m, "face_res", "", 1, 8192);
    // Probe-local bounds: any float (a probe of an empty environment stores an empty box).
    const json& box = r.member(m, "box", "");
    a.boxMin = r.vec3(box, "min", "box.", FLT_MAX);
    a.boxMax = r.vec3(box, "max", "box.", FLT_MAX);
    const json& layers = r.member(m, "layers", "");
    if (!layers.is_array() || layers.empty() || layers.size() > 256)
        throw Error(manifestPath, "layers", "expected an array of 1 to 256 layers");
    std::vector<std::string> files;
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const std::string path = "layers[" + std::to_string(i) + "].";
        const json& j = layers[i];
        DistanceProbeLayer L;
        L.name = r.string(j, "name", path);
        L.avgDistance = float(r.number(j, "avg_distance", path, 0.0, 1e9));
        L.minDistance = float(r.number(j, "min_distance", path, 0.0, 1e9));
        L.maxDistance = float(r.number(j, "max_distance", path, 0.0, 1e9));
        L.solidAngle = float(r.number(j, "solid_angle_sr", path, 0.0, 13.0));
        L.method = r.string(j, "method", path);
        // A method of the table, never a mode: a planned lookup refuses any other, and a
        // layered one would draw an unknown name as bisection without a word.
        if (const DistanceMethodInfo* m = findDistanceMethod(L.method); !m || m->glslIndex < 0)
            throw Error(manifestPath, path + "method",
                        "expected a lookup method (envmap, boxproj, bisection, secant, avgdist, "
                        "march), got '" +
                            L.method + "'");
        L.boxMin = r.vec3(j, "box_min", path, FLT_MAX);
        L.boxMax = r.vec3(j, "box_max", path, FLT_MAX);
        const json& objects = r.member(j, "objects", path);
        if (!objects.is_array()) throw Error(manifestPath, path + "objects", "expected an array");
        for (const json& o : objects) {
            if (!o.is_string())
                throw Error(manifestPath, path + "objects", "expected an array of node names");
            L.objects.push_back(o.get<std::string>());
        }
        const std::string file = r.fileInFolder(j, path, dir);
        L.file = r.string(j, "file", path);
        L.checksum = r.checksum(j, path, r.namedFile(path, [&] {
            return fileChecksum(file, maxLayerFileBytes(a.faceRes));
        }));
        // The manifest's face_res is the size the header must declare, checked before the
        // pixels are allocated (a forged header could otherwise ask for gigabytes).
        if (i == 0 && compressed) {
            L.faces = readCompressedComposite(r, j, path, dir, file, a);
            a.layers.push_back(std::move(L));
            files.push_back(file);
            continue;
        }
        const Image stacked = readKtx2Cube(file, a.faceRes);
        if (stacked.width != a.faceRes || stacked.height != 6 * a.faceRes || stacked.channels < 4)
            throw Error(file, "size",
                        "expected " + std::to_string(a.faceRes) + " x " +
                            std::to_string(6 * a.faceRes) + " RGBA, got " +
                            std::to_string(stacked.width) + " x " + std::to_string(stacked.height) +
                            " with " + std::to_string(stacked.channels) + " channels");
        L.faces = splitFaces(stacked);
        a.layers.push_back(std::move(L));
        files.push_back(file);
    }
    if (m.contains("effect_plan")) {
        if (!m["effect_plan"].is_object())
            throw Error(manifestPath, "effect_plan", "expected an object");
        a.effectPlan = m["effect_plan"].dump();
    }
    std::vector<std::string> glossyFiles;
    if (m.contains("glossy")) readGlossyLevels(r, m["glossy"], dir, a, glossyFiles);
    std::string skyFile;
    if (m.contains("sky")) {
        skyFile = r.fileInFolder(m["sky"], "sky.", dir);
        a.skyFile = r.string(m["sky"], "file", "sky.");
        a.skyChecksum = r.checksum(m["sky"], "sky.", r.namedFile("sky.", [&] {
            return fileChecksum(skyFile, kMaxSkyFileBytes);
        }));
        a.sky = readKtx2Image(skyFile);
    }
    checkContent(a, manifestPath, files, glossyFiles, skyFile);
    a.inputs = manifestProbeInputs(m, manifestPath);
    checkManifestSeal(manifest);
    return a;
}

} // namespace specula
