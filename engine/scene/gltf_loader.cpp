#include "gltf_loader.h"

#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "engine/scene/components.h"
#include "engine/scene/texture_decode.h"
#include "engine/scene/tinygltf_config.h"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>

namespace specula {

namespace {

namespace fs = std::filesystem;

// Accessors without a bufferView allocate `count` elements from nothing but a number in
// the JSON; this caps what a hostile file can make us allocate that way.
constexpr std::size_t kMaxUnbackedElements = std::size_t(1) << 26;

const std::set<std::string>& supportedRequiredExtensions() {
    static const std::set<std::string> s{"KHR_draco_mesh_compression", "KHR_mesh_quantization",
                                         "KHR_materials_unlit"};
    return s;
}

// tinygltf reports several problems separated by newlines; the project wants one line.
std::string oneLine(const std::string& text) {
    std::string out;
    std::size_t start = 0;
    while (start <= text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string part = text.substr(start, end - start);
        while (!part.empty() && std::isspace(static_cast<unsigned char>(part.back())))
            part.pop_back();
        std::size_t lead = 0;
        while (lead < part.size() && std::isspace(static_cast<unsigned char>(part[lead])))
            ++lead;
        part.erase(0, lead);
        if (!part.empty()) out += (out.empty() ? "" : "; ") + part;
        start = end + 1;
    }
    return out;
}

std::string printable(const unsigned char* p, std::size_t n) {
    std::string s;
    for (std::size_t i = 0; i < n; ++i) {
        if (p[i] >= 0x20 && p[i] < 0x7f && p[i] != '\\' && p[i] != '\'') {
            s += char(p[i]);
        } else {
            static const char* hex = "0123456789abcdef";
            s += "\\x";
            s += hex[p[i] >> 4];
            s += hex[p[i] & 15];
        }
    }
    return s;
}

std::uint32_t readLE32(const unsigned char* p) {
    return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
           (std::uint32_t(p[3]) << 24);
}

// tinygltf addresses every file with 32-bit sizes, so no glTF, buffer or image file can be
// larger.
constexpr std::uint64_t kMaxGltfFileBytes = UINT_MAX;

std::vector<unsigned char> readWholeFile(const std::string& path) {
    auto bytes = readRegularFile<std::vector<unsigned char>>(path, kMaxGltfFileBytes);
    if (bytes.empty()) throw Error(path, "", "empty file");
    return bytes;
}

// tinygltf's own file callbacks open whatever a URI names: a directory (URI ".") reads as
// SIZE_MAX bytes (std::bad_alloc), a FIFO blocks and /dev/zero never ends. These accept
// regular files only, bounded; a refusal reaches the loader as tinygltf's error or warning,
// with the reason.
bool gltfFileExists(const std::string& path, void*) {
    std::error_code ec;
    return fs::symlink_status(path, ec).type() != fs::file_type::not_found && !ec;
}
std::string gltfExpandFilePath(const std::string& path, void*) {
    return path; // no ~ or $VAR expansion: a URI is a path relative to the glTF
}
bool gltfReadWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                       void*) {
    try {
        *out = readRegularFile<std::vector<unsigned char>>(path, kMaxGltfFileBytes);
        return true;
    } catch (const Error& e) {
        if (err) *err += e.what();
        return false;
    }
}
bool gltfRefuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&,
                     void*) {
    if (err) *err += "the loader never writes files";
    return false;
}

struct GlbLayout {
    std::size_t length = 0; // bytes of the file that belong to the GLB
    const unsigned char* json = nullptr;
    std::size_t jsonSize = 0;
    bool hasBin = false;
    std::size_t binSize = 0;
    std::size_t binChunkOffset = 0; // of the chunk header
};

// Checks the GLB container before tinygltf sees it, so that every structural defect gets a
// precise message (tinygltf's own checks are coarser and miss a chunk header overrun).
GlbLayout validateGlb(const std::string& file, const std::vector<unsigned char>& b) {
    GlbLayout g;
    if (b.size() < 4 || std::memcmp(b.data(), "glTF", 4) != 0)
        throw Error(file, "header",
                    "bad magic: expected 'glTF', found '" +
                        printable(b.data(), std::min<std::size_t>(4, b.size())) + "'");
    if (b.size() < 12)
        throw Error(file, "header",
                    "truncated header: " + std::to_string(b.size()) +
                        " bytes, a GLB header needs 12");
    const std::uint32_t version = readLE32(b.data() + 4);
    if (version != 2)
        throw Error(file, "header.version",
                    "expected GLB version 2, found " + std::to_string(version));
    const std::uint32_t declared = readLE32(b.data() + 8);
    // Chunks are walked against what the file really holds, so that a cut-off file is
    // reported as the chunk it cuts.
    const std::size_t length = std::min<std::size_t>(declared, b.size());
    const std::string shortNote = declared > b.size()
                                      ? " (the file has " + std::to_string(b.size()) + " of the " +
                                            std::to_string(declared) + " bytes its header declares)"
                                      : std::string();
    if (length < 12 + 8)
        throw Error(file, "chunk 0 (JSON)",
                    "truncated chunk: no room for the JSON chunk header" + shortNote);
    g.length = length;
    std::size_t offset = 12;
    const std::uint32_t jsonLen = readLE32(b.data() + offset);
    const std::uint32_t jsonType = readLE32(b.data() + offset + 4);
    if (jsonType != 0x4E4F534Au)
        throw Error(file, "chunk 0",
                    "expected the JSON chunk (type 'JSON'), found type '" +
                        printable(b.data() + offset + 4, 4) + "'");
    if (std::uint64_t(offset) + 8 + jsonLen > length)
        throw Error(file, "chunk 0 (JSON)",
                    "truncated chunk: declares " + std::to_string(jsonLen) + " bytes but only " +
                        std::to_string(length - offset - 8) + " remain" + shortNote);
    if (jsonLen == 0) throw Error(file, "chunk 0 (JSON)", "empty JSON chunk");
    g.json = b.data() + offset + 8;
    g.jsonSize = jsonLen;
    offset += 8 + std::size_t(jsonLen);
    for (int chunk = 1; offset < length; ++chunk) {
        const std::string cf = "chunk " + std::to_string(chunk);
        if (length - offset < 8)
            throw Error(file, cf,
                        "truncated chunk: " + std::to_string(length - offset) +
                            " bytes left, a chunk header needs 8" + shortNote);
        const std::uint32_t len = readLE32(b.data() + offset);
        const std::uint32_t type = readLE32(b.data() + offset + 4);
        const bool bin = type == 0x004E4942u;
        if (std::uint64_t(offset) + 8 + len > length)
            throw Error(file, cf + (bin ? " (BIN)" : ""),
                        "truncated chunk: declares " + std::to_string(len) + " bytes but only " +
                            std::to_string(length - offset - 8) + " remain" + shortNote);
        if (bin) {
            if (g.hasBin) throw Error(file, cf, "second BIN chunk; GLB allows one");
            g.hasBin = true;
            g.binSize = len;
            g.binChunkOffset = offset;
        }
        offset += 8 + std::size_t(len);
    }
    if (declared > b.size()) throw Error(file, "header.length", "truncated file" + shortNote);
    return g;
}

std::string decodePercent(const std::string& uri) {
    std::string out;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

void checkBuffers(const std::string& file, const nlohmann::json& doc, const GlbLayout* glb);

// Buffers are checked before tinygltf loads them, because tinygltf's message for a missing
// file neither names the buffer nor says it is a buffer.
//
// Draco primitives lose their `indices` in the JSON tinygltf sees: tinygltf insists that an
// indices accessor has a bufferView, which a Draco one has not, and the loader takes the
// indices from the Draco payload anyway. Returns the JSON to hand to tinygltf when it had
// to change, nullopt otherwise.
std::optional<std::string> precheck(const std::string& file, const std::string& jsonText,
                                    const GlbLayout* glb) {
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(jsonText);
    } catch (const std::exception& e) {
        throw Error(file, "JSON", std::string("invalid JSON: ") + oneLine(e.what()));
    }
    if (!doc.is_object()) throw Error(file, "JSON", "expected a JSON object at the top level");
    checkBuffers(file, doc, glb);
    bool changed = false;
    if (auto meshes = doc.find("meshes"); meshes != doc.end() && meshes->is_array()) {
        for (auto& mesh : *meshes) {
            if (!mesh.is_object()) continue;
            auto prims = mesh.find("primitives");
            if (prims == mesh.end() || !prims->is_array()) continue;
            for (auto& prim : *prims) {
                if (!prim.is_object()) continue;
                auto ext = prim.find("extensions");
                if (ext == prim.end() || !ext->is_object() ||
                    !ext->contains("KHR_draco_mesh_compression") || !prim.contains("indices"))
                    continue;
                prim.erase("indices");
                changed = true;
            }
        }
    }
    if (!changed) return std::nullopt;
    return doc.dump();
}

void checkBuffers(const std::string& file, const nlohmann::json& doc, const GlbLayout* glb) {
    auto it = doc.find("buffers");
    if (it == doc.end()) return;
    if (!it->is_array()) throw Error(file, "buffers", "expected an array");
    const fs::path dir = fs::path(file).parent_path();
    for (std::size_t i = 0; i < it->size(); ++i) {
        const auto& buf = (*it)[i];
        const std::string field = "buffers[" + std::to_string(i) + "]";
        if (!buf.is_object()) throw Error(file, field, "expected an object");
        auto len = buf.find("byteLength");
        if (len == buf.end() || !len->is_number_unsigned())
            throw Error(file, field + ".byteLength", "expected a non-negative integer");
        const std::uint64_t byteLength = len->get<std::uint64_t>();
        auto uri = buf.find("uri");
        if (uri == buf.end()) {
            if (!glb || !glb->hasBin)
                throw Error(file, field,
                            "missing buffer: no uri and no GLB BIN chunk to take the data from");
            if (i != 0)
                throw Error(file, field, "missing buffer: only buffers[0] may use the BIN chunk");
            if (byteLength > glb->binSize)
                throw Error(file, field + ".byteLength",
                            "truncated chunk: buffer needs " + std::to_string(byteLength) +
                                " bytes but the BIN chunk has " + std::to_string(glb->binSize));
            continue;
        }
        if (!uri->is_string()) throw Error(file, field + ".uri", "expected a string");
        const std::string u = uri->get<std::string>();
        if (u.rfind("data:", 0) == 0) continue; // decoded and size-checked by tinygltf
        const fs::path p = dir / decodePercent(u);
        std::error_code ec;
        if (fs::symlink_status(p, ec).type() == fs::file_type::not_found)
            throw Error(file, field + ".uri",
                        "missing buffer: '" + u + "' not found (looked for " + p.string() + ")");
        std::uint64_t size = 0;
        try {
            size = regularFileSize(p.string(), kMaxGltfFileBytes);
        } catch (const Error& e) {
            throw Error(file, field + ".uri", "buffer '" + u + "': " + e.what());
        }
        if (size < byteLength)
            throw Error(file, field + ".uri",
                        "buffer '" + u + "' has " + std::to_string(size) +
                            " bytes, byteLength says " + std::to_string(byteLength));
    }
}

void appendLE32(std::vector<unsigned char>& v, std::uint32_t x) {
    for (int i = 0; i < 4; ++i)
        v.push_back(static_cast<unsigned char>(x >> (8 * i)));
}

// A GLB with `json` as its JSON chunk and the original BIN chunk, if any.
std::vector<unsigned char> rebuildGlb(const std::vector<unsigned char>& original,
                                      const GlbLayout& glb, std::string json) {
    while (json.size() % 4 != 0)
        json += ' ';
    const std::size_t binBytes = glb.hasBin ? 8 + glb.binSize : 0;
    const std::size_t total = 12 + 8 + json.size() + binBytes;
    std::vector<unsigned char> out;
    out.reserve(total);
    out.insert(out.end(), {'g', 'l', 'T', 'F'});
    appendLE32(out, 2);
    appendLE32(out, std::uint32_t(total));
    appendLE32(out, std::uint32_t(json.size()));
    appendLE32(out, 0x4E4F534Au);
    out.insert(out.end(), json.begin(), json.end());
    if (glb.hasBin) {
        const auto* bin = original.data() + glb.binChunkOffset;
        out.insert(out.end(), bin, bin + binBytes);
    }
    return out;
}

// Keeps images encoded: bufferView images are decoded later, after the loader has checked
// the view's range (tinygltf passes an unchecked pointer here), and only the images a
// material actually uses get decoded at all.
bool keepImageEncoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
    image->as_is = true;
    if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
    return true;
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string idx(const char* what, std::size_t i) {
    return std::string(what) + "[" + std::to_string(i) + "]";
}

struct Span {
    const unsigned char* data = nullptr;
    std::size_t stride = 0;
};

class Converter {
public:
    Converter(std::string file, const tinygltf::Model& model, LoadedScene& out)
        : file_(std::move(file)), m_(model), out_(out) {}

    [[noreturn]] void fail(const std::string& field, const std::string& what) const {
        throw Error(file_, field, what);
    }
    void warn(const std::string& field, const std::string& what) {
        out_.warnings.push_back(field + ": " + what);
    }

    template <typename T>
    const T& at(const std::vector<T>& v, int i, const char* name, const std::string& from) const {
        if (i < 0 || std::size_t(i) >= v.size())
            fail(from, std::string(name) + " index " + std::to_string(i) + " out of range (" +
                           std::to_string(v.size()) + " " + name + ")");
        return v[std::size_t(i)];
    }

    // `count` elements of `elemSize` bytes starting `offset` bytes into bufferView `view`,
    // `stride` apart (0: tightly packed, or the view's byteStride when it has one).
    Span viewRange(int view, std::size_t offset, std::size_t count, std::size_t elemSize,
                   bool useViewStride, const std::string& field) const {
        const auto& bv = at(m_.bufferViews, view, "bufferViews", field);
        const std::string vf = idx("bufferViews", std::size_t(view));
        const auto& buf = at(m_.buffers, bv.buffer, "buffers", vf);
        if (bv.byteOffset > buf.data.size() || bv.byteLength > buf.data.size() - bv.byteOffset)
            fail(vf, "byteOffset " + std::to_string(bv.byteOffset) + " + byteLength " +
                         std::to_string(bv.byteLength) + " exceeds buffers[" +
                         std::to_string(bv.buffer) + "] size " + std::to_string(buf.data.size()));
        std::size_t stride = elemSize;
        if (useViewStride && bv.byteStride != 0) {
            if (bv.byteStride < elemSize)
                fail(vf, "byteStride " + std::to_string(bv.byteStride) +
                             " is smaller than the element size " + std::to_string(elemSize));
            stride = bv.byteStride;
        }
        if (count > 0) {
            // Overflow-safe form of offset + (count-1)*stride + elemSize <= byteLength.
            const bool fits = offset <= bv.byteLength && elemSize <= bv.byteLength - offset &&
                              (count - 1) <= (bv.byteLength - offset - elemSize) / stride;
            if (!fits)
                fail(field, "accessor out of range: " + std::to_string(count) + " elements of " +
                                std::to_string(elemSize) + " bytes, stride " +
                                std::to_string(stride) + ", from offset " + std::to_string(offset) +
                                " do not fit in " + vf + " (" + std::to_string(bv.byteLength) +
                                " bytes)");
        }
        return {buf.data.data() + bv.byteOffset + offset, stride};
    }

    static std::size_t componentBytes(int componentType) {
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
        default:
            return 0;
        }
    }

    // One component as double; `normalized` applies glTF's normalised-integer mapping.
    static double component(int type, const unsigned char* p, bool normalized) {
        switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            std::int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t v;
            std::memcpy(&v, p, 4);
            return normalized ? v / 4294967295.0 : v;
        }
        default: {
            float v;
            std::memcpy(&v, p, 4);
            return v;
        }
        }
    }

    // Reads accessor `index` into `comps` values per element, fully range-checked,
    // including sparse substitution.
    template <typename T>
    std::vector<T> readAccessor(int index, int comps, bool integerOnly, const std::string& from) {
        const auto& acc = at(m_.accessors, index, "accessors", from);
        const std::string af = idx("accessors", std::size_t(index));
        const int have = tinygltf::GetNumComponentsInType(std::uint32_t(acc.type));
        if (have != comps)
            fail(af + ".type", "expected " + std::string(comps == 1 ? "SCALAR" : "VEC") +
                                   (comps == 1 ? "" : std::to_string(comps)) + " for " + from);
        const std::size_t cb = componentBytes(acc.componentType);
        const bool isInt = acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
        if (cb == 0 ||
            (integerOnly && (!isInt || acc.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
                             acc.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)))
            fail(af + ".componentType",
                 "unsupported componentType " + std::to_string(acc.componentType) + " for " + from);
        const std::size_t count = acc.count;
        const std::size_t elem = cb * std::size_t(comps);
        const bool norm = acc.normalized && !integerOnly;
        std::vector<T> out;
        if (acc.bufferView < 0) {
            if (count > kMaxUnbackedElements)
                fail(af + ".count", "count " + std::to_string(count) + " without a bufferView");
            out.assign(count * std::size_t(comps), T(0));
        } else {
            const Span s = viewRange(acc.bufferView, acc.byteOffset, count, elem, true, af);
            out.resize(count * std::size_t(comps));
            for (std::size_t i = 0; i < count; ++i)
                for (int c = 0; c < comps; ++c)
                    out[i * std::size_t(comps) + std::size_t(c)] = static_cast<T>(component(
                        acc.componentType, s.data + i * s.stride + std::size_t(c) * cb, norm));
        }
        if (acc.sparse.isSparse) {
            const auto& sp = acc.sparse;
            const std::string sf = af + ".sparse";
            if (sp.count < 0 || std::size_t(sp.count) > count)
                fail(sf + ".count", "sparse count " + std::to_string(sp.count) +
                                        " exceeds the accessor count " + std::to_string(count));
            const std::size_t n = std::size_t(sp.count);
            const int it = sp.indices.componentType;
            const std::size_t ib = componentBytes(it);
            if (ib == 0 || it == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                it == TINYGLTF_COMPONENT_TYPE_BYTE || it == TINYGLTF_COMPONENT_TYPE_SHORT)
                fail(sf + ".indices.componentType", "expected an unsigned integer type");
            if (sp.indices.byteOffset < 0 || sp.values.byteOffset < 0)
                fail(sf, "negative byteOffset");
            const Span is = viewRange(sp.indices.bufferView, std::size_t(sp.indices.byteOffset), n,
                                      ib, false, sf + ".indices");
            const Span vs = viewRange(sp.values.bufferView, std::size_t(sp.values.byteOffset), n,
                                      elem, false, sf + ".values");
            for (std::size_t k = 0; k < n; ++k) {
                const double target = component(it, is.data + k * is.stride, false);
                if (target >= double(count))
                    fail(sf + ".indices", "index out of range: " + std::to_string(target) +
                                              " >= count " + std::to_string(count));
                for (int c = 0; c < comps; ++c)
                    out[std::size_t(target) * std::size_t(comps) + std::size_t(c)] = static_cast<T>(
                        component(acc.componentType, vs.data + k * vs.stride + std::size_t(c) * cb,
                                  norm));
            }
        }
        return out;
    }

    std::vector<glm::vec3> readVec3(int index, const std::string& from) {
        const auto raw = readAccessor<float>(index, 3, false, from);
        std::vector<glm::vec3> v(raw.size() / 3);
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] = {raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]};
        return v;
    }
    std::vector<glm::vec2> readVec2(int index, const std::string& from) {
        const auto raw = readAccessor<float>(index, 2, false, from);
        std::vector<glm::vec2> v(raw.size() / 2);
        for (std::size_t i = 0; i < v.size(); ++i)
            v[i] = {raw[2 * i], raw[2 * i + 1]};
        return v;
    }

    // KHR_draco_mesh_compression: decodes the payload and fills the attributes it carries.
    void decodeDraco(const tinygltf::Primitive& prim, const tinygltf::Value& ext,
                     const std::string& field, MeshData& md, bool& hasNormals, bool& hasUvs) {
        const std::string ef = field + ".extensions.KHR_draco_mesh_compression";
        if (!ext.IsObject()) fail(ef, "expected an object");
        const tinygltf::Value& bvv = ext.Get("bufferView");
        const tinygltf::Value& attrs = ext.Get("attributes");
        if (!bvv.IsInt()) fail(ef + ".bufferView", "expected an integer");
        if (!attrs.IsObject()) fail(ef + ".attributes", "expected an object");
        const int view = bvv.Get<int>();
        const auto& bv = at(m_.bufferViews, view, "bufferViews", ef + ".bufferView");
        const Span s = viewRange(view, 0, bv.byteLength > 0 ? 1 : 0, bv.byteLength, false, ef);
        if (bv.byteLength == 0) fail(ef, "undecodable Draco payload: empty bufferView");

        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(s.data), bv.byteLength);
        std::unique_ptr<draco::Mesh> mesh;
        try {
            auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
            if (!type.ok())
                fail(ef, "undecodable Draco payload in " + idx("bufferViews", std::size_t(view)) +
                             ": " + oneLine(type.status().error_msg_string()));
            if (type.value() != draco::TRIANGULAR_MESH)
                fail(ef, "undecodable Draco payload in " + idx("bufferViews", std::size_t(view)) +
                             ": not a triangle mesh");
            draco::Decoder decoder;
            auto result = decoder.DecodeMeshFromBuffer(&buffer);
            if (!result.ok())
                fail(ef, "undecodable Draco payload in " + idx("bufferViews", std::size_t(view)) +
                             ": " + oneLine(result.status().error_msg_string()));
            mesh = std::move(result).value();
        } catch (const std::bad_alloc&) {
            fail(ef, "undecodable Draco payload in " + idx("bufferViews", std::size_t(view)) +
                         ": decoder ran out of memory");
        }
        if (!mesh) fail(ef, "undecodable Draco payload: decoder returned no mesh");

        const std::size_t points = mesh->num_points();
        auto readAttr = [&](const char* name, int comps, auto& dst) -> bool {
            const tinygltf::Value& id = attrs.Get(name);
            if (!id.IsInt()) {
                // Attributes outside the extension come from ordinary accessors.
                auto a = prim.attributes.find(name);
                if (a == prim.attributes.end()) return false;
                if constexpr (std::is_same_v<std::decay_t<decltype(dst)>, std::vector<glm::vec3>>)
                    dst = readVec3(a->second, field + ".attributes." + name);
                else
                    dst = readVec2(a->second, field + ".attributes." + name);
                if (dst.size() != points)
                    fail(field + ".attributes." + name,
                         "count " + std::to_string(dst.size()) + " differs from the " +
                             std::to_string(points) + " Draco points");
                return true;
            }
            const draco::PointAttribute* pa =
                mesh->GetAttributeByUniqueId(std::uint32_t(id.Get<int>()));
            if (!pa)
                fail(ef + ".attributes." + name, "undecodable Draco payload: attribute id " +
                                                     std::to_string(id.Get<int>()) +
                                                     " is not in the payload");
            if (pa->num_components() != comps)
                fail(ef + ".attributes." + name,
                     "Draco attribute has " + std::to_string(int(pa->num_components())) +
                         " components, expected " + std::to_string(comps));
            dst.resize(points);
            float tmp[4] = {0, 0, 0, 0};
            for (std::size_t i = 0; i < points; ++i) {
                const draco::AttributeValueIndex vi =
                    pa->mapped_index(draco::PointIndex(std::uint32_t(i)));
                if (vi.value() >= pa->size() ||
                    !pa->ConvertValue<float>(vi, std::int8_t(comps), tmp))
                    fail(ef + ".attributes." + name, "undecodable Draco payload: point " +
                                                         std::to_string(i) +
                                                         " maps to no attribute value");
                for (int c = 0; c < comps; ++c)
                    dst[i][c] = tmp[c];
            }
            // glTF says the accessor describes the decoded data; a disagreement is worth a note.
            auto a = prim.attributes.find(name);
            if (a != prim.attributes.end() && a->second >= 0 &&
                std::size_t(a->second) < m_.accessors.size() &&
                m_.accessors[std::size_t(a->second)].count != points)
                warn(ef, std::string(name) + " accessor count " +
                             std::to_string(m_.accessors[std::size_t(a->second)].count) +
                             " differs from the " + std::to_string(points) + " decoded points");
            return true;
        };
        if (!readAttr("POSITION", 3, md.positions)) fail(field + ".attributes", "no POSITION");
        hasNormals = readAttr("NORMAL", 3, md.normals);
        hasUvs = readAttr("TEXCOORD_0", 2, md.uvs);

        md.indices.resize(std::size_t(mesh->num_faces()) * 3);
        for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
            const auto& face = mesh->face(f);
            for (int k = 0; k < 3; ++k)
                md.indices[std::size_t(f.value()) * 3 + std::size_t(k)] = face[k].value();
        }
    }

    std::shared_ptr<const MeshData> buildPrimitive(const tinygltf::Primitive& prim,
                                                   const std::string& field) {
        auto md = std::make_shared<MeshData>();
        bool hasNormals = false, hasUvs = false;
        auto draco = prim.extensions.find("KHR_draco_mesh_compression");
        if (draco != prim.extensions.end()) {
            decodeDraco(prim, draco->second, field, *md, hasNormals, hasUvs);
        } else {
            auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) fail(field + ".attributes", "no POSITION");
            md->positions = readVec3(pos->second, field + ".attributes.POSITION");
            const std::size_t n = md->positions.size();
            if (auto a = prim.attributes.find("NORMAL"); a != prim.attributes.end()) {
                md->normals = readVec3(a->second, field + ".attributes.NORMAL");
                hasNormals = true;
                if (md->normals.size() != n)
                    fail(field + ".attributes.NORMAL", "count differs from POSITION's");
            }
            if (auto a = prim.attributes.find("TEXCOORD_0"); a != prim.attributes.end()) {
                md->uvs = readVec2(a->second, field + ".attributes.TEXCOORD_0");
                hasUvs = true;
                if (md->uvs.size() != n)
                    fail(field + ".attributes.TEXCOORD_0", "count differs from POSITION's");
            }
            if (prim.indices >= 0) {
                md->indices =
                    readAccessor<std::uint32_t>(prim.indices, 1, true, field + ".indices");
            } else {
                if (n > std::size_t(UINT32_MAX)) fail(field, "too many vertices");
                md->indices.resize(n);
                std::iota(md->indices.begin(), md->indices.end(), 0u);
            }
        }
        const std::size_t n = md->positions.size();
        for (std::size_t i = 0; i < n; ++i)
            if (!finite(md->positions[i]))
                fail(field + ".attributes.POSITION",
                     "non-finite position at vertex " + std::to_string(i));
        for (std::size_t k = 0; k < md->indices.size(); ++k)
            if (md->indices[k] >= n)
                fail(field + ".indices", "index out of range: indices[" + std::to_string(k) +
                                             "] = " + std::to_string(md->indices[k]) +
                                             " but only " + std::to_string(n) + " vertices");
        if (md->indices.size() % 3 != 0) {
            warn(field, "index count " + std::to_string(md->indices.size()) +
                            " is not a multiple of 3; the incomplete triangle is dropped");
            md->indices.resize(md->indices.size() - md->indices.size() % 3);
        }
        if (hasUvs)
            for (auto& uv : md->uvs)
                if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.f);
        if (!hasUvs) md->uvs.clear();
        repairNormals(*md, hasNormals);
        if (n > 0) {
            md->boundsMin = md->boundsMax = md->positions[0];
            for (const auto& p : md->positions) {
                md->boundsMin = glm::min(md->boundsMin, p);
                md->boundsMax = glm::max(md->boundsMax, p);
            }
        }
        return md;
    }

    // Area-weighted vertex normals where the asset gives none, or gives zero/NaN ones:
    // the unnormalised face cross product is twice the triangle's area, which is the weight.
    static void repairNormals(MeshData& md, bool hasNormals) {
        const std::size_t n = md.positions.size();
        std::vector<glm::vec3> generated;
        auto generate = [&] {
            generated.assign(n, glm::vec3(0.f));
            for (std::size_t t = 0; t + 2 < md.indices.size(); t += 3) {
                const std::uint32_t a = md.indices[t], b = md.indices[t + 1], c = md.indices[t + 2];
                const glm::vec3 f = glm::cross(md.positions[b] - md.positions[a],
                                               md.positions[c] - md.positions[a]);
                if (!finite(f)) continue;
                generated[a] += f;
                generated[b] += f;
                generated[c] += f;
            }
        };
        auto usable = [](const glm::vec3& v) {
            const float l = glm::dot(v, v);
            return finite(v) && std::isfinite(l) && l > 1e-24f;
        };
        if (!hasNormals) md.normals.assign(n, glm::vec3(0.f));
        for (std::size_t i = 0; i < n; ++i) {
            glm::vec3 v = md.normals[i];
            if (!usable(v)) {
                if (generated.empty()) generate();
                v = generated[i];
            }
            // A vertex of degenerate triangles only has no defined normal; any unit vector
            // keeps shading finite.
            md.normals[i] = usable(v) ? glm::normalize(v) : glm::vec3(0.f, 1.f, 0.f);
        }
    }

    std::shared_ptr<const Image> baseColorImage(int textureIndex, const std::string& from) {
        const auto& tex = at(m_.textures, textureIndex, "textures", from);
        const std::string tf = idx("textures", std::size_t(textureIndex));
        const int source = tex.source;
        const auto& img = at(m_.images, source, "images", tf + ".source");
        if (auto it = images_.find(source); it != images_.end()) return it->second;
        const std::string imf = idx("images", std::size_t(source));
        const unsigned char* data = nullptr;
        std::size_t size = 0;
        if (img.bufferView >= 0) {
            const auto& bv = at(m_.bufferViews, img.bufferView, "bufferViews", imf + ".bufferView");
            const Span s =
                viewRange(img.bufferView, 0, bv.byteLength > 0 ? 1 : 0, bv.byteLength, false, imf);
            data = s.data;
            size = bv.byteLength;
        } else {
            data = img.image.data();
            size = img.image.size();
            if (size == 0) fail(imf + ".uri", "cannot read image '" + img.uri + "'");
        }
        std::string why;
        auto decoded = decodeTexture8(data, size, true, why);
        if (!decoded) fail(imf, "undecodable image: " + why);
        auto ptr = std::make_shared<const Image>(std::move(*decoded));
        images_[source] = ptr;
        return ptr;
    }

    std::shared_ptr<const MaterialData> material(int index, const std::string& from) {
        if (auto it = materials_.find(index); it != materials_.end()) return it->second;
        auto md = std::make_shared<MaterialData>();
        if (index >= 0) {
            const auto& mat = at(m_.materials, index, "materials", from);
            const std::string mf = idx("materials", std::size_t(index));
            md->name = mat.name;
            md->doubleSided = mat.doubleSided;
            const auto& f = mat.pbrMetallicRoughness.baseColorFactor;
            if (f.size() != 4)
                fail(mf + ".pbrMetallicRoughness.baseColorFactor", "expected 4 numbers");
            for (int c = 0; c < 4; ++c) {
                if (!std::isfinite(f[std::size_t(c)]))
                    fail(mf + ".pbrMetallicRoughness.baseColorFactor", "non-finite value");
                md->baseColorFactor[c] = float(f[std::size_t(c)]);
            }
            const auto& bct = mat.pbrMetallicRoughness.baseColorTexture;
            if (bct.index >= 0) {
                if (bct.texCoord != 0)
                    warn(mf, "baseColorTexture uses TEXCOORD_" + std::to_string(bct.texCoord) +
                                 "; only TEXCOORD_0 is loaded");
                md->baseColorTexture =
                    baseColorImage(bct.index, mf + ".pbrMetallicRoughness.baseColorTexture");
            }
        } else {
            md->name = "default";
        }
        materials_[index] = md;
        return md;
    }

    const Mesh& mesh(int index, const std::string& from) {
        const auto& gm = at(m_.meshes, index, "meshes", from);
        if (auto it = meshes_.find(index); it != meshes_.end()) return it->second;
        Mesh mesh;
        mesh.name = gm.name;
        const std::string mf = idx("meshes", std::size_t(index));
        for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
            const auto& prim = gm.primitives[p];
            const std::string pf = mf + ".primitives[" + std::to_string(p) + "]";
            if (prim.mode != TINYGLTF_MODE_TRIANGLES) {
                warn(pf, "mode " + std::to_string(prim.mode) +
                             " skipped; only TRIANGLES (4) is loaded");
                continue;
            }
            Primitive out;
            out.mesh = buildPrimitive(prim, pf);
            out.material = material(prim.material, pf + ".material");
            out_.primitives += 1;
            out_.vertices += out.mesh->positions.size();
            out_.triangles += out.mesh->indices.size() / 3;
            mesh.primitives.push_back(std::move(out));
        }
        out_.meshes += 1;
        return meshes_.emplace(index, std::move(mesh)).first->second;
    }

    Camera camera(int index, const std::string& from, bool& ok) {
        const auto& c = at(m_.cameras, index, "cameras", from);
        const std::string cf = idx("cameras", std::size_t(index));
        ok = false;
        Camera cam;
        if (c.type != "perspective") {
            warn(cf, "camera type '" + c.type + "' skipped; only perspective is loaded");
            return cam;
        }
        const auto& p = c.perspective;
        if (!std::isfinite(p.yfov) || p.yfov <= 0.0 || p.yfov >= 3.14159)
            fail(cf + ".perspective.yfov", "expected an angle in (0, pi) radians");
        if (!std::isfinite(p.znear) || p.znear <= 0.0)
            fail(cf + ".perspective.znear", "expected a positive number");
        if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0)
            fail(cf + ".perspective.aspectRatio", "expected a positive number");
        if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && p.zfar <= p.znear))
            fail(cf + ".perspective.zfar", "expected a number larger than znear");
        cam.yfov = float(p.yfov);
        cam.aspect = float(p.aspectRatio);
        cam.znear = float(p.znear);
        // glTF leaves zfar out for an infinite projection; keep the component's finite
        // default, far enough for every scene this project draws.
        if (p.zfar > 0.0) cam.zfar = float(p.zfar);
        ok = true;
        return cam;
    }

    // Local TRS of a node; matrices are decomposed (shear cannot be represented and is
    // reported).
    Transform localTransform(const tinygltf::Node& node, const std::string& nf) {
        Transform t;
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(nf + ".matrix", "expected 16 numbers");
            glm::mat4 m;
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) {
                    const double v = node.matrix[std::size_t(c * 4 + r)];
                    if (!std::isfinite(v)) fail(nf + ".matrix", "non-finite value");
                    m[c][r] = float(v);
                }
            t.translation = glm::vec3(m[3]);
            glm::vec3 cols[3] = {glm::vec3(m[0]), glm::vec3(m[1]), glm::vec3(m[2])};
            glm::vec3 s(glm::length(cols[0]), glm::length(cols[1]), glm::length(cols[2]));
            if (glm::determinant(glm::mat3(m)) < 0.f) s.x = -s.x;
            t.scale = s;
            if (std::abs(s.x) > 1e-12f && std::abs(s.y) > 1e-12f && std::abs(s.z) > 1e-12f) {
                const glm::mat3 r(cols[0] / s.x, cols[1] / s.y, cols[2] / s.z);
                t.rotation = glm::normalize(glm::quat_cast(r));
                const glm::mat3 rtr = glm::transpose(r) * r;
                float dev = 0.f;
                for (int a = 0; a < 3; ++a)
                    for (int b = 0; b < 3; ++b)
                        dev = std::max(dev, std::abs(rtr[a][b] - (a == b ? 1.f : 0.f)));
                if (dev > 1e-3f) warn(nf + ".matrix", "shear dropped when decomposing into TRS");
            }
            return t;
        }
        auto vec = [&](const std::vector<double>& v, std::size_t n, const char* name, float* dst) {
            if (v.empty()) return;
            if (v.size() != n) fail(nf + "." + name, "expected " + std::to_string(n) + " numbers");
            for (std::size_t i = 0; i < n; ++i) {
                if (!std::isfinite(v[i])) fail(nf + "." + name, "non-finite value");
                dst[i] = float(v[i]);
            }
        };
        vec(node.translation, 3, "translation", &t.translation.x);
        vec(node.scale, 3, "scale", &t.scale.x);
        float q[4] = {0.f, 0.f, 0.f, 1.f}; // glTF order x, y, z, w
        vec(node.rotation, 4, "rotation", q);
        const glm::quat rot(q[3], q[0], q[1], q[2]);
        const float len = glm::length(rot);
        if (!(len > 1e-6f)) fail(nf + ".rotation", "expected a unit quaternion, got length 0");
        t.rotation = rot / len;
        return t;
    }

    struct NodeDesc {
        int node = -1;
        int parent = -1; // index into the descs vector
        Transform transform;
        const Mesh* mesh = nullptr;
        std::optional<Camera> camera;
    };

    void convert(ecs::Registry& registry) {
        // glTF 2.x only: a major version this loader does not know may mean anything.
        const std::string& version = m_.asset.version;
        if (version.empty() || version.substr(0, version.find('.')) != "2")
            fail("asset.version", "expected a glTF 2.x version, got '" + version + "'");
        if (!m_.asset.minVersion.empty() && m_.asset.minVersion.substr(0, 2) != "2.")
            fail("asset.minVersion", "expected 2.x, got '" + m_.asset.minVersion + "'");
        for (const auto& ext : m_.extensionsRequired)
            if (!supportedRequiredExtensions().count(ext))
                fail("extensionsRequired", "requires unsupported extension '" + ext + "'");
        out_.extensionsUsed = m_.extensionsUsed;

        std::vector<int> roots;
        if (!m_.scenes.empty()) {
            const int s = m_.defaultScene >= 0 ? m_.defaultScene : 0;
            roots = at(m_.scenes, s, "scenes", "scene").nodes;
        } else {
            std::vector<char> isChild(m_.nodes.size(), 0);
            for (std::size_t i = 0; i < m_.nodes.size(); ++i)
                for (int c : m_.nodes[i].children)
                    if (c >= 0 && std::size_t(c) < m_.nodes.size()) isChild[std::size_t(c)] = 1;
            for (std::size_t i = 0; i < m_.nodes.size(); ++i)
                if (!isChild[i]) roots.push_back(int(i));
        }

        // Depth-first, parents before children, with an explicit stack so that a deep or
        // cyclic hierarchy in a hostile file cannot overflow the call stack.
        std::vector<NodeDesc> descs;
        std::vector<char> seen(m_.nodes.size(), 0);
        std::vector<std::pair<int, int>> stack; // node, parent desc
        for (auto it = roots.rbegin(); it != roots.rend(); ++it)
            stack.emplace_back(*it, -1);
        while (!stack.empty()) {
            const auto [ni, parent] = stack.back();
            stack.pop_back();
            const auto& node =
                at(m_.nodes, ni, "nodes",
                   parent < 0
                       ? std::string("scene.nodes")
                       : idx("nodes", std::size_t(descs[std::size_t(parent)].node)) + ".children");
            const std::string nf = idx("nodes", std::size_t(ni));
            if (seen[std::size_t(ni)])
                fail(nf, "node reached twice in the hierarchy (shared child or cycle)");
            seen[std::size_t(ni)] = 1;
            NodeDesc d;
            d.node = ni;
            d.parent = parent;
            d.transform = localTransform(node, nf);
            d.transform.world = d.transform.local();
            if (parent >= 0)
                d.transform.world = descs[std::size_t(parent)].transform.world * d.transform.world;
            if (node.mesh >= 0)
                d.mesh = &mesh(node.mesh, nf + ".mesh");
            else if (node.mesh < -1)
                fail(nf + ".mesh", "negative index");
            if (node.camera >= 0) {
                bool ok = false;
                Camera c = camera(node.camera, nf + ".camera", ok);
                if (ok) d.camera = c;
            }
            descs.push_back(std::move(d));
            const int self = int(descs.size() - 1);
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
                stack.emplace_back(*c, self);
        }

        // World bounds over every instance; vertices are transformed exactly, not just the
        // corners of the local box, so rotated instances do not inflate the bounds.
        bool any = false;
        glm::vec3 lo(0.f), hi(0.f);
        for (const auto& d : descs) {
            if (!d.mesh) continue;
            for (const auto& p : d.mesh->primitives)
                for (const auto& v : p.mesh->positions) {
                    const glm::vec3 w = glm::vec3(d.transform.world * glm::vec4(v, 1.f));
                    if (!any) lo = hi = w;
                    lo = glm::min(lo, w);
                    hi = glm::max(hi, w);
                    any = true;
                }
        }
        if (!finite(lo) || !finite(hi)) fail("nodes", "world-space bounds are not finite");
        out_.boundsMin = lo;
        out_.boundsMax = hi;
        std::set<const MaterialData*> mats;
        for (const auto& [i, mesh] : meshes_)
            for (const auto& p : mesh.primitives)
                mats.insert(p.material.get());
        out_.materials = mats.size();

        // Only now touch the registry: a failure above leaves it unchanged.
        std::vector<ecs::Entity> entities(descs.size());
        for (std::size_t i = 0; i < descs.size(); ++i) {
            const NodeDesc& d = descs[i];
            const tinygltf::Node& node = m_.nodes[std::size_t(d.node)];
            const ecs::Entity e = registry.create();
            entities[i] = e;
            registry.emplace<Name>(
                e, Name{node.name.empty() ? "node_" + std::to_string(d.node) : node.name});
            Transform t = d.transform;
            t.parent = d.parent >= 0 ? entities[std::size_t(d.parent)] : ecs::kNullEntity;
            registry.emplace<Transform>(e, t);
            registry.emplace<SceneNode>(e, SceneNode{d.node});
            if (d.mesh) registry.emplace<Mesh>(e, *d.mesh);
            if (d.camera) registry.emplace<Camera>(e, *d.camera);
            if (!node.extras_json_string.empty())
                registry.emplace<Extras>(e, Extras{node.extras_json_string});
            out_.entities.push_back(e);
            if (d.parent < 0) out_.roots.push_back(e);
        }
        out_.nodes = descs.size();
    }

private:
    std::string file_;
    const tinygltf::Model& m_;
    LoadedScene& out_;
    std::map<int, Mesh> meshes_;
    std::map<int, std::shared_ptr<const MaterialData>> materials_;
    std::map<int, std::shared_ptr<const Image>> images_;
};

} // namespace

LoadedScene loadGltf(const std::string& path, ecs::Registry& registry) {
    const std::vector<unsigned char> bytes = readWholeFile(path);
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });

    std::optional<GlbLayout> glb;
    std::string jsonText;
    if (binary || ext == ".glb") {
        glb = validateGlb(path, bytes);
        jsonText.assign(reinterpret_cast<const char*>(glb->json), glb->jsonSize);
    } else {
        jsonText.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    }
    const std::optional<std::string> rewritten = precheck(path, jsonText, glb ? &*glb : nullptr);
    std::vector<unsigned char> rebuilt; // a GLB around the rewritten JSON
    const unsigned char* glbBytes = bytes.data();
    std::size_t glbSize = glb ? glb->length : 0;
    if (rewritten) {
        jsonText = *rewritten;
        if (glb) {
            rebuilt = rebuildGlb(bytes, *glb, jsonText);
            glbBytes = rebuilt.data();
            glbSize = rebuilt.size();
        }
    }

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&gltfFileExists, &gltfExpandFilePath,
                                                &gltfReadWholeFile, &gltfRefuseWrite, nullptr});
    loader.SetImageLoader(&keepImageEncoded, nullptr);
    loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
    tinygltf::Model model;
    std::string err, warn;
    const std::string baseDir = fs::path(path).parent_path().string();
    bool ok = false;
    try {
        if (glb)
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glbBytes,
                                             static_cast<unsigned int>(glbSize), baseDir);
        else
            ok = loader.LoadASCIIFromString(&model, &err, &warn, jsonText.data(),
                                            static_cast<unsigned int>(jsonText.size()), baseDir);
    } catch (const std::exception& e) {
        throw Error(path, "", std::string("glTF parse failed: ") + oneLine(e.what()));
    }
    if (!ok) {
        const std::string why = oneLine(err);
        throw Error(path, "", "glTF parse failed: " + (why.empty() ? "unknown reason" : why));
    }

    LoadedScene scene;
    for (const std::string& w : {oneLine(warn)})
        if (!w.empty()) scene.warnings.push_back("tinygltf: " + w);
    Converter converter(path, model, scene);
    converter.convert(registry);
    return scene;
}

} // namespace specula
