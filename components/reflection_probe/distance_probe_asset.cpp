#include "distance_probe_asset.h"

#include "components/reflection_probe/probe_folder.h"

#include "engine/core/error.h"
#include "engine/image/image_io.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <unistd.h>

namespace fs = std::filesystem;
using nlohmann::json;

namespace specula {

std::string fileChecksum(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "", "cannot open file for its checksum");
    std::uint64_t h = 0xcbf29ce484222325ull;
    char buf[1 << 16];
    while (in) {
        in.read(buf, sizeof buf);
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            h ^= static_cast<unsigned char>(buf[i]);
            h *= 0x100000001b3ull;
        }
    }
    char hex[32];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
    return std::string("fnv1a64:") + hex;
}

namespace {

json vec3Json(glm::vec3 v) {
    return json::array({v.x, v.y, v.z});
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

// Typed field access that names the file and the JSON path on every failure.
struct Reader {
    const std::string& file;

    const json& member(const json& obj, const std::string& key, const std::string& path) const {
        if (!obj.is_object() || !obj.contains(key))
            throw Error(file, path + key, "missing (expected a value here)");
        return obj.at(key);
    }
    float number(const json& obj, const std::string& key, const std::string& path, float lo,
                 float hi) const {
        const json& v = member(obj, key, path);
        if (!v.is_number()) throw Error(file, path + key, "expected a number");
        const double d = v.get<double>();
        if (!std::isfinite(d) || d < lo || d > hi)
            throw Error(file, path + key,
                        "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                            "], got " + v.dump());
        return float(d);
    }
    std::string string(const json& obj, const std::string& key, const std::string& path) const {
        const json& v = member(obj, key, path);
        if (!v.is_string()) throw Error(file, path + key, "expected a string");
        return v.get<std::string>();
    }
    glm::vec3 vec3(const json& obj, const std::string& key, const std::string& path) const {
        const json& v = member(obj, key, path);
        if (!v.is_array() || v.size() != 3)
            throw Error(file, path + key, "expected an array of 3 numbers");
        glm::vec3 out;
        for (int i = 0; i < 3; ++i) {
            if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
                throw Error(file, path + key, "expected an array of 3 finite numbers");
            out[i] = v[i].get<float>();
        }
        return out;
    }
    // A file named in the manifest: relative, inside the probe folder, checksum matching.
    std::string checkedFile(const json& obj, const std::string& path, const fs::path& dir,
                            std::string& checksumOut) const {
        const std::string name = string(obj, "file", path);
        if (name.empty() || fs::path(name).is_absolute() || name.find("..") != std::string::npos)
            throw Error(file, path + "file", "expected a plain file name inside the probe folder");
        const std::string full = (dir / name).string();
        if (!fs::exists(full)) throw Error(file, path + "file", "names missing file " + full);
        checksumOut = string(obj, "checksum", path);
        const std::string actual = fileChecksum(full);
        if (actual != checksumOut)
            throw Error(file, path + "checksum",
                        "mismatch for " + name + ": manifest says " + checksumOut + ", file has " +
                            actual);
        return full;
    }
};

} // namespace

void writeDistanceProbe(const DistanceProbeAsset& asset, const std::string& dir,
                        const std::string& sourceScene) {
    writeProbeFolder(dir, [&](const fs::path& tmp) {
        json layers = json::array();
        for (std::size_t i = 0; i < asset.layers.size(); ++i) {
            const DistanceProbeLayer& L = asset.layers[i];
            char name[64];
            std::snprintf(name, sizeof name, "layer_%02zu.exr", i);
            const std::string path = (tmp / name).string();
            writeImage(path, stackFaces(L.faces));
            layers.push_back({{"name", L.name},
                              {"order", i},
                              {"objects", L.objects},
                              {"avg_distance", L.avgDistance},
                              {"min_distance", L.minDistance},
                              {"max_distance", L.maxDistance},
                              {"solid_angle_sr", L.solidAngle},
                              {"box_min", vec3Json(L.boxMin)},
                              {"box_max", vec3Json(L.boxMax)},
                              {"method", L.method},
                              {"file", name},
                              {"checksum", fileChecksum(path)}});
        }
        json manifest = {
            {"format", "specula-probe"},
            {"version", kProbeFormatVersion},
            {"flavour", "distance"},
            {"source", sourceScene},
            {"centre", vec3Json(asset.centre)},
            {"range_D", asset.range},
            {"d_inf", asset.dInf},
            {"face_res", asset.faceRes},
            {"box", {{"min", vec3Json(asset.boxMin)}, {"max", vec3Json(asset.boxMax)}}},
            {"face_layout", "N x 6N EXR, faces +X -X +Y -Y +Z -Z top to bottom, "
                            "RGB radiance, A distance from the centre"},
            {"layers", layers}};
        if (!asset.effectPlan.empty()) manifest["effect_plan"] = json::parse(asset.effectPlan);
        if (!asset.sky.empty()) {
            const std::string path = (tmp / "sky.exr").string();
            writeImage(path, asset.sky);
            manifest["sky"] = {{"file", "sky.exr"}, {"checksum", fileChecksum(path)}};
        }
        return manifest;
    });
}

DistanceProbeAsset readDistanceProbe(const std::string& manifestPath) {
    std::ifstream in(manifestPath, std::ios::binary);
    if (!in) throw Error(manifestPath, "", "cannot open manifest");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error(manifestPath, "", "read failed");
    return parseDistanceProbe(text, manifestPath);
}

DistanceProbeAsset parseDistanceProbe(const std::string& manifestText,
                                      const std::string& manifestPath) {
    json m;
    try {
        m = json::parse(manifestText);
    } catch (const json::exception& e) {
        throw Error(manifestPath, "", std::string("not valid JSON: ") + e.what());
    }
    const Reader r{manifestPath};
    const fs::path dir = fs::path(manifestPath).parent_path();
    if (r.string(m, "format", "") != "specula-probe")
        throw Error(manifestPath, "format", "expected \"specula-probe\"");
    const float version = r.number(m, "version", "", 0.f, 1e6f);
    if (version != float(kProbeFormatVersion))
        throw Error(manifestPath, "version",
                    "unknown format version " + m["version"].dump() + " (this build reads " +
                        std::to_string(kProbeFormatVersion) + ")");
    if (r.string(m, "flavour", "") != "distance")
        throw Error(manifestPath, "flavour", "expected \"distance\"");

    DistanceProbeAsset a;
    a.centre = r.vec3(m, "centre", "");
    a.range = r.number(m, "range_D", "", 1e-6f, 1e7f);
    a.dInf = r.number(m, "d_inf", "", 1e-6f, 1e9f);
    a.faceRes = int(r.number(m, "face_res", "", 1.f, 8192.f));
    const json& box = r.member(m, "box", "");
    a.boxMin = r.vec3(box, "min", "box.");
    a.boxMax = r.vec3(box, "max", "box.");
    const json& layers = r.member(m, "layers", "");
    if (!layers.is_array() || layers.empty() || layers.size() > 256)
        throw Error(manifestPath, "layers", "expected an array of 1 to 256 layers");
    for (std::size_t i = 0; i < layers.size(); ++i) {
        const std::string path = "layers[" + std::to_string(i) + "].";
        DistanceProbeLayer L;
        L.name = r.string(layers[i], "name", path);
        L.avgDistance = r.number(layers[i], "avg_distance", path, 0.f, 1e9f);
        L.minDistance = r.number(layers[i], "min_distance", path, 0.f, 1e9f);
        L.maxDistance = r.number(layers[i], "max_distance", path, 0.f, 1e9f);
        L.solidAngle = r.number(layers[i], "solid_angle_sr", path, 0.f, 13.f);
        L.method = r.string(layers[i], "method", path);
        L.boxMin = r.vec3(layers[i], "box_min", path);
        L.boxMax = r.vec3(layers[i], "box_max", path);
        if (const json& objs = r.member(layers[i], "objects", path); objs.is_array()) {
            for (const json& o : objs)
                if (o.is_string()) L.objects.push_back(o.get<std::string>());
        }
        const std::string file = r.checkedFile(layers[i], path, dir, L.checksum);
        L.file = r.string(layers[i], "file", path);
        const Image stacked = readImage(file, false);
        if (stacked.width != a.faceRes || stacked.height != 6 * a.faceRes || stacked.channels < 4)
            throw Error(file, "size",
                        "expected " + std::to_string(a.faceRes) + " x " +
                            std::to_string(6 * a.faceRes) + " RGBA, got " +
                            std::to_string(stacked.width) + " x " + std::to_string(stacked.height) +
                            " with " + std::to_string(stacked.channels) + " channels");
        L.faces = splitFaces(stacked);
        a.layers.push_back(std::move(L));
    }
    if (m.contains("effect_plan")) {
        if (!m["effect_plan"].is_object())
            throw Error(manifestPath, "effect_plan", "expected an object");
        a.effectPlan = m["effect_plan"].dump();
    }
    if (m.contains("sky")) {
        const std::string file = r.checkedFile(m["sky"], "sky.", dir, a.skyChecksum);
        a.skyFile = r.string(m["sky"], "file", "sky.");
        a.sky = readImage(file, false);
    }
    return a;
}

} // namespace specula
