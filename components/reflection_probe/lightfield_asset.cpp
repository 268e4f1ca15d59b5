#include "lightfield_asset.h"

#include "components/reflection_probe/probe_folder.h"

#include "components/reflection_probe/distance_probe_asset.h" // fileChecksum, kProbeFormatVersion
#include "engine/core/error.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
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
    auto field = [&](const char* flag, const char* key) {
        return source.empty() ? std::string(flag) : std::string(key);
    };
    if (cameras < 2 || cameras > 256)
        throw Error(source, field("--cameras", "cameras"),
                    "expected 2 to 256 cameras per side, got " + std::to_string(cameras));
    if (res < 4 || res > 4096 || res % 4 != 0)
        throw Error(source, field("--image-res", "image_res"),
                    "expected a multiple of 4 in [4, 4096] (BC1 blocks must not straddle two "
                    "cameras), got " +
                        std::to_string(res));
    if (cameras * res > 16384)
        throw Error(source, field("--cameras", "cameras"),
                    "NUM x RES = " + std::to_string(cameras * res) +
                        " exceeds the 16384 texel side of a 2D texture atlas");
    if (!(cellSize > 0.f) || !std::isfinite(cellSize))
        throw Error(source, field("--cell-size", "cell.size"), "expected a positive size");
    (void)c;
}

namespace {

json vec3Json(glm::vec3 v) {
    return json::array({v.x, v.y, v.z});
}
// JSON has no infinity: +inf depths are written as null.
json depthJson(float d) {
    return std::isinf(d) ? json(nullptr) : json(d);
}

// Typed manifest access naming the file and the JSON path on every failure.
struct Fields {
    const std::string& file;

    const json& member(const json& obj, const std::string& key, const std::string& path) const {
        if (!obj.is_object() || !obj.contains(key))
            throw Error(file, path + key, "missing (expected a value here)");
        return obj.at(key);
    }
    double number(const json& obj, const std::string& key, const std::string& path, double lo,
                  double hi, bool nullIsInf = false) const {
        const json& v = member(obj, key, path);
        if (nullIsInf && v.is_null()) return std::numeric_limits<double>::infinity();
        if (!v.is_number()) throw Error(file, path + key, "expected a number");
        const double d = v.get<double>();
        if (!std::isfinite(d) || d < lo || d > hi)
            throw Error(file, path + key,
                        "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                            "], got " + v.dump());
        return d;
    }
    int integer(const json& obj, const std::string& key, const std::string& path, int lo,
                int hi) const {
        const double d = number(obj, key, path, lo, hi);
        if (d != std::floor(d)) throw Error(file, path + key, "expected an integer");
        return int(d);
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
};

void writeBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw Error(path.string(), "", "write failed");
}

// --- BC1 -----------------------------------------------------------------------------------

std::uint16_t pack565(glm::vec3 c) {
    const int r = std::clamp(int(std::lround(c.r * 31.f / 255.f)), 0, 31);
    const int g = std::clamp(int(std::lround(c.g * 63.f / 255.f)), 0, 63);
    const int b = std::clamp(int(std::lround(c.b * 31.f / 255.f)), 0, 31);
    return std::uint16_t((r << 11) | (g << 5) | b);
}

glm::ivec3 unpack565(std::uint16_t v) {
    const int r = (v >> 11) & 31, g = (v >> 5) & 63, b = v & 31;
    return {(r << 3) | (r >> 2), (g << 2) | (g >> 4), (b << 3) | (b >> 2)};
}

// The four-colour palette of a block with c0 > c1 (the only mode the encoder writes).
void palette(std::uint16_t c0, std::uint16_t c1, glm::ivec3 out[4]) {
    out[0] = unpack565(c0);
    out[1] = unpack565(c1);
    if (c0 > c1) {
        out[2] = (2 * out[0] + out[1]) / 3;
        out[3] = (out[0] + 2 * out[1]) / 3;
    } else {
        out[2] = (out[0] + out[1]) / 2;
        out[3] = glm::ivec3(0);
    }
}

// One block: endpoints at the extremes of the colours along their principal axis (a few
// power iterations on the covariance), then each texel takes the nearest palette entry.
void encodeBlock(const glm::vec3 px[16], std::uint8_t out[8]) {
    glm::vec3 mean(0.f);
    for (int i = 0; i < 16; ++i)
        mean += px[i];
    mean /= 16.f;
    float cov[6] = {};
    for (int i = 0; i < 16; ++i) {
        const glm::vec3 d = px[i] - mean;
        cov[0] += d.r * d.r, cov[1] += d.r * d.g, cov[2] += d.r * d.b;
        cov[3] += d.g * d.g, cov[4] += d.g * d.b, cov[5] += d.b * d.b;
    }
    glm::vec3 axis(0.57735f);
    for (int it = 0; it < 6; ++it) {
        const glm::vec3 next(cov[0] * axis.r + cov[1] * axis.g + cov[2] * axis.b,
                             cov[1] * axis.r + cov[3] * axis.g + cov[4] * axis.b,
                             cov[2] * axis.r + cov[4] * axis.g + cov[5] * axis.b);
        const float len = glm::length(next);
        if (!(len > 1e-12f)) break;
        axis = next / len;
    }
    float lo = std::numeric_limits<float>::max(), hi = -lo;
    for (int i = 0; i < 16; ++i) {
        const float t = glm::dot(px[i] - mean, axis);
        lo = std::min(lo, t);
        hi = std::max(hi, t);
    }
    std::uint16_t c0 = pack565(glm::clamp(mean + hi * axis, 0.f, 255.f));
    std::uint16_t c1 = pack565(glm::clamp(mean + lo * axis, 0.f, 255.f));
    if (c0 < c1) std::swap(c0, c1);
    std::uint32_t indices = 0;
    if (c0 != c1) {
        glm::ivec3 pal[4];
        palette(c0, c1, pal);
        for (int i = 0; i < 16; ++i) {
            int best = 0;
            float bestD = std::numeric_limits<float>::max();
            for (int k = 0; k < 4; ++k) {
                const glm::vec3 d = px[i] - glm::vec3(pal[k]);
                const float dd = glm::dot(d, d);
                if (dd < bestD) bestD = dd, best = k;
            }
            indices |= std::uint32_t(best) << (2 * i);
        }
    }
    // c0 == c1: every index 0 (c0); the block is a single colour.
    out[0] = std::uint8_t(c0 & 0xff), out[1] = std::uint8_t(c0 >> 8);
    out[2] = std::uint8_t(c1 & 0xff), out[3] = std::uint8_t(c1 >> 8);
    for (int k = 0; k < 4; ++k)
        out[4 + k] = std::uint8_t(indices >> (8 * k));
}

} // namespace

std::vector<std::uint8_t> encodeBC1(const std::uint8_t* rgb, int width, int height) {
    const int bw = width / 4, bh = height / 4;
    std::vector<std::uint8_t> out(std::size_t(bw) * bh * 8);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            glm::vec3 px[16];
            for (int y = 0; y < 4; ++y)
                for (int x = 0; x < 4; ++x) {
                    const std::uint8_t* p =
                        rgb + (std::size_t(by * 4 + y) * width + std::size_t(bx * 4 + x)) * 3;
                    px[y * 4 + x] = glm::vec3(p[0], p[1], p[2]);
                }
            encodeBlock(px, &out[(std::size_t(by) * bw + bx) * 8]);
        }
    return out;
}

std::vector<std::uint8_t> decodeBC1(const std::uint8_t* blocks, int width, int height) {
    const int bw = width / 4, bh = height / 4;
    std::vector<std::uint8_t> out(std::size_t(width) * height * 3);
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            const std::uint8_t* b = blocks + (std::size_t(by) * bw + bx) * 8;
            glm::ivec3 pal[4];
            palette(std::uint16_t(b[0] | (b[1] << 8)), std::uint16_t(b[2] | (b[3] << 8)), pal);
            const std::uint32_t idx = std::uint32_t(b[4]) | (std::uint32_t(b[5]) << 8) |
                                      (std::uint32_t(b[6]) << 16) | (std::uint32_t(b[7]) << 24);
            for (int i = 0; i < 16; ++i) {
                const glm::ivec3 c = pal[(idx >> (2 * i)) & 3];
                std::uint8_t* p =
                    &out[(std::size_t(by * 4 + i / 4) * width + std::size_t(bx * 4 + i % 4)) * 3];
                p[0] = std::uint8_t(c.r), p[1] = std::uint8_t(c.g), p[2] = std::uint8_t(c.b);
            }
        }
    return out;
}

void writeLightFieldProbe(const LightFieldAsset& a, const std::string& dir,
                          const std::string& sourceScene) {
    validateLightFieldSize(a.cameras, a.res, a.cellSize, a.compression, "");
    writeProbeFolder(dir, [&](const fs::path& tmp) {
        json slabs = json::array();
        for (int k = 0; k < 6; ++k) {
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
        json manifest = {
            {"format", "specula-probe"},
            {"version", kProbeFormatVersion},
            {"flavour", "lightfield"},
            {"source", sourceScene},
            {"cell", {{"centre", vec3Json(a.cellCentre)}, {"size", a.cellSize}}},
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
            {"slabs", slabs}};
        return manifest;
    });
}

namespace {
json parseManifest(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path, "", "cannot open manifest");
    try {
        return json::parse(in);
    } catch (const json::parse_error& e) {
        throw Error(path, "", std::string("not valid JSON: ") + e.what());
    }
}
} // namespace

std::string probeManifestFlavour(const std::string& manifestPath) {
    const json m = parseManifest(manifestPath);
    return Fields{manifestPath}.string(m, "flavour", "");
}

LightFieldAsset readLightFieldProbe(const std::string& manifestPath) {
    const json m = parseManifest(manifestPath);
    const Fields r{manifestPath};
    const fs::path dir = fs::path(manifestPath).parent_path();
    if (r.string(m, "format", "") != "specula-probe")
        throw Error(manifestPath, "format", "expected \"specula-probe\"");
    if (r.integer(m, "version", "", 0, 1000000) != kProbeFormatVersion)
        throw Error(manifestPath, "version",
                    "unknown format version " + m["version"].dump() + " (this build reads " +
                        std::to_string(kProbeFormatVersion) + ")");
    if (const std::string f = r.string(m, "flavour", ""); f != "lightfield")
        throw Error(manifestPath, "flavour", "expected \"lightfield\", got \"" + f + "\"");

    LightFieldAsset a;
    const json& cell = r.member(m, "cell", "");
    a.cellCentre = r.vec3(cell, "centre", "cell.");
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
    a.depthPercentile = float(r.number(m, "depth_percentile", "", 0.0, 0.5));
    if (m.contains("bake") && m["bake"].contains("seconds") && m["bake"]["seconds"].is_number())
        a.bakeSeconds = m["bake"]["seconds"].get<double>();
    if (m.contains("intrusions") && m["intrusions"].is_array())
        for (const json& i : m["intrusions"])
            if (i.is_object() && i.contains("object") && i["object"].is_string())
                a.intrusions.push_back({i["object"].get<std::string>(),
                                        i.value("region", std::string()), i.value("depth_m", 0.f)});

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
        s.nearDepth = float(r.number(j, "depth_near", path, 0.0, 1e9, true));
        s.farDepth = float(r.number(j, "depth_far", path, 0.0, 1e9, true));
        s.minDepth = float(r.number(j, "depth_min", path, 0.0, 1e9));
        s.maxDepth = float(r.number(j, "depth_max", path, 0.0, 1e9));
        s.skyFraction = float(r.number(j, "sky_fraction", path, 0.0, 1.0));
        s.intrudingFraction = float(r.number(j, "intruding_fraction", path, 0.0, 1.0));
        s.focalDepth = float(r.number(j, "focal_depth", path, 0.0, 1e9, true));
        s.disparity = float(r.number(j, "disparity_px", path, 0.0, 1e6));
        s.file = r.string(j, "file", path);
        if (s.file.empty() || fs::path(s.file).is_absolute() ||
            s.file.find("..") != std::string::npos || s.file.find('/') != std::string::npos)
            throw Error(manifestPath, path + "file",
                        "expected a plain file name inside the probe folder");
        const std::string full = (dir / s.file).string();
        if (!fs::exists(full))
            throw Error(manifestPath, path + "file", "names missing file " + full);
        s.checksum = r.string(j, "checksum", path);
        if (const std::string actual = fileChecksum(full); actual != s.checksum)
            throw Error(manifestPath, path + "checksum",
                        "mismatch for " + s.file + ": manifest says " + s.checksum + ", file has " +
                            actual);
        const std::size_t size = std::size_t(fs::file_size(full));
        if (size != a.layerBytes())
            throw Error(full, "size",
                        "expected " + std::to_string(a.layerBytes()) + " bytes (" +
                            std::to_string(a.atlasSize()) + "^2 " + toString(a.compression) +
                            "), got " + std::to_string(size));
        s.data.resize(size);
        std::ifstream in(full, std::ios::binary);
        in.read(reinterpret_cast<char*>(s.data.data()), std::streamsize(size));
        if (!in) throw Error(full, "", "read failed");
    }
    return a;
}

} // namespace specula
