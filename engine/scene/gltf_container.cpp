#include "gltf_container.h"

#include "engine/core/error.h"
#include "engine/core/regular_file.h"
#include "engine/scene/gltf_context.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace specula::gltf_internal {

namespace {

constexpr std::uint32_t kChunkJson = 0x4E4F534Au; // 'JSON'
constexpr std::uint32_t kChunkBin = 0x004E4942u;  // 'BIN\0'

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

void writeLE32(unsigned char* p, std::uint32_t x) {
    for (int i = 0; i < 4; ++i)
        p[i] = static_cast<unsigned char>(x >> (8 * i));
}

// The 12-byte header: magic, version 2, and the length it declares.
std::uint32_t checkHeader(const std::string& file, const std::vector<unsigned char>& b) {
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
    return readLE32(b.data() + 8);
}

// Where the chunks are walked: the file's bytes, up to `length`, and how to say that the
// file holds fewer bytes than its header declares.
struct ChunkWalk {
    const std::string& file;
    const std::vector<unsigned char>& bytes;
    std::size_t length;
    std::string shortNote;

    void checkFits(std::size_t offset, std::uint32_t len, const std::string& field) const {
        if (std::uint64_t(offset) + 8 + len > length)
            throw Error(file, field,
                        "truncated chunk: declares " + std::to_string(len) + " bytes but only " +
                            std::to_string(length - offset - 8) + " remain" + shortNote);
    }
};

// Chunk 0, which must be the JSON; returns the offset of the next chunk.
std::size_t readJsonChunk(const ChunkWalk& w, GlbLayout& g) {
    if (w.length < 12 + 8)
        throw Error(w.file, "chunk 0 (JSON)",
                    "truncated chunk: no room for the JSON chunk header" + w.shortNote);
    const std::size_t offset = 12;
    const std::uint32_t jsonLen = readLE32(w.bytes.data() + offset);
    const std::uint32_t jsonType = readLE32(w.bytes.data() + offset + 4);
    if (jsonType != kChunkJson)
        throw Error(w.file, "chunk 0",
                    "expected the JSON chunk (type 'JSON'), found type '" +
                        printable(w.bytes.data() + offset + 4, 4) + "'");
    w.checkFits(offset, jsonLen, "chunk 0 (JSON)");
    if (jsonLen == 0) throw Error(w.file, "chunk 0 (JSON)", "empty JSON chunk");
    g.json = w.bytes.data() + offset + 8;
    g.jsonSize = jsonLen;
    return offset + 8 + std::size_t(jsonLen);
}

// The chunks after the JSON: each must fit, and at most one may be BIN.
void readLaterChunks(const ChunkWalk& w, std::size_t offset, GlbLayout& g) {
    for (int chunk = 1; offset < w.length; ++chunk) {
        const std::string cf = "chunk " + std::to_string(chunk);
        if (w.length - offset < 8)
            throw Error(w.file, cf,
                        "truncated chunk: " + std::to_string(w.length - offset) +
                            " bytes left, a chunk header needs 8" + w.shortNote);
        const std::uint32_t len = readLE32(w.bytes.data() + offset);
        const bool bin = readLE32(w.bytes.data() + offset + 4) == kChunkBin;
        w.checkFits(offset, len, cf + (bin ? " (BIN)" : ""));
        if (bin) {
            if (g.hasBin) throw Error(w.file, cf, "second BIN chunk; GLB allows one");
            g.hasBin = true;
            g.binSize = len;
            g.binChunkOffset = offset;
        }
        offset += 8 + std::size_t(len);
    }
}

} // namespace

std::vector<unsigned char> readWholeFile(const std::string& path) {
    auto bytes = readRegularFile<std::vector<unsigned char>>(path, kMaxGltfFileBytes);
    if (bytes.empty()) throw Error(path, "", "empty file");
    return bytes;
}

GlbLayout validateGlb(const std::string& file, const std::vector<unsigned char>& b) {
    const std::uint32_t declared = checkHeader(file, b);
    // Chunks are walked against what the file really holds, so that a cut-off file is
    // reported as the chunk it cuts.
    const ChunkWalk walk{file, b, std::min<std::size_t>(declared, b.size()),
                         declared > b.size()
                             ? " (the file has " + std::to_string(b.size()) + " of the " +
                                   std::to_string(declared) + " bytes its header declares)"
                             : std::string()};
    GlbLayout g;
    g.length = walk.length;
    readLaterChunks(walk, readJsonChunk(walk, g), g);
    if (declared > b.size()) throw Error(file, "header.length", "truncated file" + walk.shortNote);
    return g;
}

std::vector<unsigned char> rebuildGlb(const std::vector<unsigned char>& original,
                                      const GlbLayout& glb, std::string json) {
    while (json.size() % 4 != 0)
        json += ' ';
    const std::size_t binBytes = glb.hasBin ? 8 + glb.binSize : 0;
    const std::size_t total = 12 + 8 + json.size() + binBytes;
    // Filled in place: GCC 12 misreads insert-after-reserve as an overflow.
    std::vector<unsigned char> out(total);
    std::memcpy(out.data(), "glTF", 4);
    writeLE32(out.data() + 4, 2);
    writeLE32(out.data() + 8, std::uint32_t(total));
    writeLE32(out.data() + 12, std::uint32_t(json.size()));
    writeLE32(out.data() + 16, kChunkJson);
    std::memcpy(out.data() + 20, json.data(), json.size());
    if (glb.hasBin)
        std::memcpy(out.data() + 20 + json.size(), original.data() + glb.binChunkOffset, binBytes);
    return out;
}

} // namespace specula::gltf_internal
