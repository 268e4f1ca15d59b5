#include "lightfield_asset.h"

#include "components/reflection_probe/probe_folder.h"

#include "components/reflection_probe/distance_probe_asset.h" // checksums, kProbeFormatVersion
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/core/regular_file.h"

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

namespace {

// A BC1 block the GPU cannot decode to a colour: with c0 <= c1 a block is in BC1's
// three-colour mode, where index 3 means transparent black. The baker never writes it (its
// blocks have c0 > c1, or c0 == c1 with every index 0); random or damaged bytes hit it in
// about half their blocks. Returns the index of the first such block, or -1.
long firstUndecodableBC1Block(const std::vector<std::uint8_t>& data) {
    for (std::size_t b = 0; b + 8 <= data.size(); b += 8) {
        const std::uint8_t* p = &data[b];
        const unsigned c0 = unsigned(p[0] | (p[1] << 8)), c1 = unsigned(p[2] | (p[3] << 8));
        if (c0 > c1) continue;
        for (int i = 0; i < 16; ++i)
            if (((p[4 + i / 4] >> (2 * (i % 4))) & 3) == 3) return long(b / 8);
    }
    return -1;
}

// The figures of one slab against each other: what the bake derives from its depth
// histogram (near <= focal <= far, disparity from the focal depth, disjoint fractions).
void checkSlabFigures(const LightFieldAsset& a, const LightFieldSlab& s,
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
        checkSlabFigures(a, s, manifest, "slabs[" + std::to_string(k) + "].");
        if (a.compression == LightFieldCompression::BC1)
            if (const long b = firstUndecodableBC1Block(s.data); b >= 0)
                throw Error(manifest, "slabs[" + std::to_string(k) + "]",
                            "BC1 block " + std::to_string(b) + " is not decodable");
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

std::string probeManifestFlavour(const std::string& manifestPath) {
    const json m = parseManifestJson(readManifestText(manifestPath), manifestPath);
    return ManifestFields{manifestPath}.string(m, "flavour", "");
}

LightFieldAsset readLightFieldProbe(const std::string& manifestPath) {
    return parseLightFieldProbe(readManifestText(manifestPath), manifestPath);
}

LightFieldAsset parseLightFieldProbe(const std::string& manifestText,
                                     const std::string& manifestPath) {
    const json m = parseManifestJson(manifestText, manifestPath);
    const ManifestFields r{manifestPath};
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
        checkSlabFigures(a, s, manifestPath, path);
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
            if (const long b = firstUndecodableBC1Block(s.data); b >= 0)
                throw Error(full, "texels",
                            "BC1 block " + std::to_string(b) +
                                " is in the three-colour mode the baker never writes (its "
                                "index 3 decodes to transparent black)");
    }
    return a;
}

} // namespace specula
