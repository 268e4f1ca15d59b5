#include "gltf_prepass.h"

#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "engine/scene/gltf_context.h"

#include <nlohmann/json.hpp>

#include <cctype>
#include <filesystem>

namespace specula::gltf_internal {

namespace {

namespace fs = std::filesystem;

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

// A buffer without a uri takes its bytes from the GLB's BIN chunk.
void checkBinBuffer(const std::string& file, const std::string& field, std::size_t i,
                    std::uint64_t byteLength, const GlbLayout* glb) {
    if (!glb || !glb->hasBin)
        throw Error(file, field,
                    "missing buffer: no uri and no GLB BIN chunk to take the data from");
    if (i != 0) throw Error(file, field, "missing buffer: only buffers[0] may use the BIN chunk");
    if (byteLength > glb->binSize)
        throw Error(file, field + ".byteLength",
                    "truncated chunk: buffer needs " + std::to_string(byteLength) +
                        " bytes but the BIN chunk has " + std::to_string(glb->binSize));
}

// A buffer in a file beside the glTF: it must exist, be a regular file and be long enough.
void checkBufferFile(const std::string& file, const std::string& field, const std::string& u,
                     std::uint64_t byteLength) {
    const fs::path p = fs::path(file).parent_path() / decodePercent(u);
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
                    "buffer '" + u + "' has " + std::to_string(size) + " bytes, byteLength says " +
                        std::to_string(byteLength));
}

void checkBuffers(const std::string& file, const nlohmann::json& doc, const GlbLayout* glb) {
    auto it = doc.find("buffers");
    if (it == doc.end()) return;
    if (!it->is_array()) throw Error(file, "buffers", "expected an array");
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
            checkBinBuffer(file, field, i, byteLength, glb);
            continue;
        }
        if (!uri->is_string()) throw Error(file, field + ".uri", "expected a string");
        const std::string u = uri->get<std::string>();
        if (u.rfind("data:", 0) == 0) continue; // decoded and size-checked by tinygltf
        checkBufferFile(file, field, u, byteLength);
    }
}

// Drops `indices` from every Draco primitive; true when there was one to drop.
bool dropDracoIndices(nlohmann::json& doc) {
    bool changed = false;
    auto meshes = doc.find("meshes");
    if (meshes == doc.end() || !meshes->is_array()) return false;
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
    return changed;
}

} // namespace

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
    if (!dropDracoIndices(doc)) return std::nullopt;
    return doc.dump();
}

} // namespace specula::gltf_internal
