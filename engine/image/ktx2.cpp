#include "engine/image/ktx2.h"

#include "engine/image/bc6h.h"

#include "engine/core/error.h"
#include "engine/core/file_write.h"
#include "engine/core/regular_file.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>

namespace specula {
namespace {

static_assert(std::endian::native == std::endian::little,
              "KTX2 is little-endian; so is this reader");

constexpr const unsigned char (&kIdentifier)[12] = kKtx2Identifier;
constexpr std::size_t kHeaderBytes = 80; // identifier, 9 header words, the index
constexpr std::size_t kLevelIndexBytes = 24;
// Larger than any GL implementation's texture size, small enough that sizes never overflow.
constexpr std::uint32_t kMaxDimension = 1u << 16;

// VK_FORMAT_R*_SFLOAT by channel count - 1: 16-bit, 32-bit.
constexpr std::uint32_t kHalfFormats[4] = {76, 83, 90, 97};
constexpr std::uint32_t kFloatFormats[4] = {100, 103, 106, 109};
// Khronos Data Format: channel ids of RGBSDA (R, G, B, alpha) and the sample qualifiers.
constexpr std::uint32_t kChannelIds[4] = {0, 1, 2, 15};
constexpr std::uint32_t kQualifierFloatSigned = 0x80 | 0x40;
constexpr std::uint32_t kFloatMinusOne = 0xBF800000u, kFloatOne = 0x3F800000u;
// VK_FORMAT_BC6H_UFLOAT_BLOCK and its colour model, KHR_DF_MODEL_BC6H.
constexpr std::uint32_t kBc6hFormat = 131, kBc6hModel = 133;

struct Layout {
    int channels = 4;
    bool half = false;
    bool bc6h = false; // 16-byte blocks of 4x4 RGB texels
    // Bytes of a texel, or of a block.
    std::size_t texelBytes() const {
        return bc6h ? kBc6hBlockBytes : std::size_t(channels) * (half ? 2 : 4);
    }
    std::uint32_t typeSize() const { return bc6h ? 1 : half ? 2 : 4; }
    // Level data starts at a multiple of lcm(texel or block size, 4) (the spec's mip padding).
    std::size_t alignment() const { return std::lcm(texelBytes(), std::size_t(4)); }
    std::uint32_t vkFormat() const {
        return bc6h ? kBc6hFormat : (half ? kHalfFormats : kFloatFormats)[channels - 1];
    }
    // Bytes of one face of a level of w x h.
    std::size_t faceBytes(int w, int h) const {
        return bc6h ? bc6hBytes(w, h) : std::size_t(w) * std::size_t(h) * texelBytes();
    }
};

std::size_t alignUp(std::size_t n, std::size_t a) {
    return (n + a - 1) / a * a;
}

// The one-block DFD of a layout, words after dfdTotalSize included.
std::vector<std::uint32_t> dataFormatDescriptor(const Layout& l) {
    if (l.bc6h) // one 128-bit sample of the colour channel (0), float, unsigned; 4x4 texels
        return {44,
                0,
                2u | 40u << 16,
                kBc6hModel | 1u << 8 | 1u << 16,
                3u | 3u << 8,
                16,
                0,
                127u << 16 | 0x80u << 24,
                0,
                0,
                kFloatOne};
    const std::uint32_t blockBytes = 24 + 16 * std::uint32_t(l.channels);
    std::vector<std::uint32_t> w = {4 + blockBytes,
                                    0,                     // vendor Khronos, type basic
                                    2u | blockBytes << 16, // version 2
                                    1u | 1u << 8 |
                                        1u << 16, // RGBSDA, BT.709, linear, straight alpha
                                    0,            // 1x1x1x1 texel block
                                    std::uint32_t(l.texelBytes()),
                                    0};
    const std::uint32_t bits = l.half ? 16 : 32;
    for (int c = 0; c < l.channels; ++c) {
        w.push_back(std::uint32_t(c) * bits | (bits - 1) << 16 |
                    (kChannelIds[c] | kQualifierFloatSigned) << 24);
        w.push_back(0); // sample position
        w.push_back(kFloatMinusOne);
        w.push_back(kFloatOne);
    }
    return w;
}

template <typename T> void put(std::string& out, T v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <typename T> T get(const std::string& bytes, std::size_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;
}

int faceCount(const Ktx2Texture& t) {
    return t.cube ? 6 : 1;
}

void appendLevel(std::string& out, const Image& image, bool half) {
    if (!half) {
        out.append(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size() * 4);
        return;
    }
    for (float v : image.pixels)
        put(out, std::uint16_t(glm::packHalf1x16(v)));
}

// The checked header fields, for errors and the level walk.
struct Header {
    std::uint32_t vkFormat, typeSize, width, height, depth, layers, faces, levels, scheme;
    std::uint32_t dfdOffset, dfdLength, kvdOffset, kvdLength;
    std::uint64_t sgdOffset, sgdLength;
};

Header readHeader(const std::string& b, const std::string& name) {
    if (b.size() < kHeaderBytes || std::memcmp(b.data(), kIdentifier, sizeof kIdentifier) != 0)
        throw Error(name, "identifier", "not a KTX 2.0 file");
    Header h{};
    std::uint32_t* words[] = {&h.vkFormat,  &h.typeSize,  &h.width,    &h.height, &h.depth,
                              &h.layers,    &h.faces,     &h.levels,   &h.scheme, &h.dfdOffset,
                              &h.dfdLength, &h.kvdOffset, &h.kvdLength};
    for (std::size_t i = 0; i < std::size(words); ++i)
        *words[i] = get<std::uint32_t>(b, 12 + 4 * i);
    h.sgdOffset = get<std::uint64_t>(b, 64);
    h.sgdLength = get<std::uint64_t>(b, 72);
    return h;
}

Layout layoutOf(const Header& h, const std::string& name) {
    if (h.vkFormat == kBc6hFormat) return {3, false, true};
    for (int c = 1; c <= 4; ++c) {
        if (h.vkFormat == kFloatFormats[c - 1]) return {c, false};
        if (h.vkFormat == kHalfFormats[c - 1]) return {c, true};
    }
    throw Error(name, "vkFormat",
                std::to_string(h.vkFormat) +
                    " is not a 16- or 32-bit float R/RG/RGB/RGBA format, nor BC6H unsigned");
}

void checkRange(std::uint64_t offset, std::uint64_t length, std::size_t fileSize,
                const std::string& name, const std::string& field) {
    if (offset > fileSize || length > fileSize - offset)
        throw Error(name, field,
                    "bytes " + std::to_string(offset) + " + " + std::to_string(length) +
                        " run past the end of the file (" + std::to_string(fileSize) + " bytes)");
}

void checkDfd(const std::string& b, const Header& h, const Layout& l, const std::string& name) {
    const std::vector<std::uint32_t> want = dataFormatDescriptor(l);
    if (h.dfdLength != want.size() * 4 || get<std::uint32_t>(b, h.dfdOffset) != h.dfdLength)
        throw Error(name, "dfd",
                    "expected one basic descriptor block of " +
                        std::to_string(l.bc6h ? 1 : l.channels) + " samples");
    auto word = [&](std::size_t i) { return get<std::uint32_t>(b, h.dfdOffset + 4 * i); };
    // Vendor, type, version, model, primaries, transfer, block size, bytes per plane, and
    // per sample its bits, channel and float qualifier: what decoding depends on. The
    // sample bounds are informative for float formats and not compared.
    for (std::size_t i = 1; i < want.size(); ++i) {
        const bool bounds = i >= 7 && (i - 7) % 4 >= 2;
        const std::uint32_t mask = i == 3 ? 0x00FFFFFFu : 0xFFFFFFFFu; // flags: alpha mode free
        if (!bounds && (word(i) & mask) != (want[i] & mask))
            throw Error(name, "dfd",
                        "word " + std::to_string(i) + " does not describe vkFormat " +
                            std::to_string(h.vkFormat) +
                            (l.bc6h ? " (linear BC6H unsigned float blocks)"
                                    : " (linear RGBSDA float samples)"));
    }
}

std::map<std::string, std::string> readKeyValues(const std::string& b, const Header& h,
                                                 const std::string& name) {
    std::map<std::string, std::string> kv;
    std::size_t at = h.kvdOffset;
    const std::size_t end = std::size_t(h.kvdOffset) + h.kvdLength;
    while (at < end) {
        if (end - at < 4) throw Error(name, "kvd", "truncated entry length");
        const std::uint32_t n = get<std::uint32_t>(b, at);
        if (n > end - at - 4) throw Error(name, "kvd", "an entry runs past the key/value data");
        const std::string entry = b.substr(at + 4, n);
        const std::size_t nul = entry.find('\0');
        if (nul == std::string::npos || nul == 0)
            throw Error(name, "kvd", "an entry without a NUL-terminated key");
        std::string value = entry.substr(nul + 1);
        if (!value.empty() && value.back() == '\0') value.pop_back();
        kv[entry.substr(0, nul)] = value;
        at += alignUp(4 + n, 4);
    }
    return kv;
}

} // namespace

Ktx2Texture parseKtx2(const std::string& b, const std::string& name, const Ktx2ReadLimits& limits) {
    const Header h = readHeader(b, name);
    const Layout l = layoutOf(h, name);
    if (h.typeSize != l.typeSize())
        throw Error(name, "typeSize", "expected " + std::to_string(l.typeSize()));
    if (h.width == 0 || h.height == 0) throw Error(name, "pixelHeight", "a 2D image has a height");
    if (h.width > kMaxDimension || h.height > kMaxDimension)
        throw Error(name, "pixelWidth",
                    std::to_string(h.width) + " x " + std::to_string(h.height) + " is over " +
                        std::to_string(kMaxDimension) + " a side");
    if (h.depth != 0) throw Error(name, "pixelDepth", "3D textures are not supported");
    if (h.layers != 0) throw Error(name, "layerCount", "array textures are not supported");
    if (h.faces != 1 && h.faces != 6) throw Error(name, "faceCount", "expected 1 or 6");
    if (h.faces == 6 && h.width != h.height)
        throw Error(name, "pixelHeight", "a cube map's faces are square");
    if (h.scheme != 0) throw Error(name, "supercompressionScheme", "expected 0 (none)");
    const std::uint32_t maxLevels = std::uint32_t(std::bit_width(std::max(h.width, h.height)));
    if (h.levels == 0 || h.levels > maxLevels)
        throw Error(name, "levelCount",
                    std::to_string(h.levels) + " levels for " + std::to_string(h.width) + " x " +
                        std::to_string(h.height) + " (1 to " + std::to_string(maxLevels) + ")");
    if (limits.width > 0 &&
        (h.width != std::uint32_t(limits.width) || h.height != std::uint32_t(limits.height)))
        throw Error(name, "pixelWidth",
                    std::to_string(h.width) + " x " + std::to_string(h.height) + ", expected " +
                        std::to_string(limits.width) + " x " + std::to_string(limits.height));
    if (limits.faces > 0 && h.faces != std::uint32_t(limits.faces))
        throw Error(name, "faceCount", "expected " + std::to_string(limits.faces));
    if (limits.channels > 0 && l.channels != limits.channels)
        throw Error(name, "vkFormat", "expected " + std::to_string(limits.channels) + " channels");
    if (b.size() < kHeaderBytes + kLevelIndexBytes * h.levels)
        throw Error(name, "levelCount", "the level index runs past the end of the file");
    checkRange(h.dfdOffset, h.dfdLength, b.size(), name, "dfdByteOffset");
    checkRange(h.kvdOffset, h.kvdLength, b.size(), name, "kvdByteOffset");
    checkRange(h.sgdOffset, h.sgdLength, b.size(), name, "sgdByteOffset");
    if (h.dfdOffset % 4 != 0 || h.kvdOffset % 4 != 0)
        throw Error(name, "dfdByteOffset", "the DFD and key/value data are 4-byte aligned");
    checkDfd(b, h, l, name);

    Ktx2Texture t;
    t.cube = h.faces == 6;
    t.halfFloat = l.half;
    t.bc6h = l.bc6h;
    t.keyValues = readKeyValues(b, h, name);
    std::uint64_t values = 0;
    for (std::uint32_t k = 0; k < h.levels; ++k) {
        const std::uint64_t w = std::max(1u, h.width >> k), hh = std::max(1u, h.height >> k);
        values += w * hh * h.faces * std::uint64_t(l.channels);
    }
    if (values > limits.maxValues)
        throw Error(name, "pixelWidth",
                    "holds " + std::to_string(values) + " values, more than the " +
                        std::to_string(limits.maxValues) + " allowed");
    for (std::uint32_t k = 0; k < h.levels; ++k) {
        const std::string field = "level " + std::to_string(k);
        const std::size_t at = kHeaderBytes + kLevelIndexBytes * k;
        const std::uint64_t offset = get<std::uint64_t>(b, at),
                            length = get<std::uint64_t>(b, at + 8);
        const int w = int(std::max(1u, h.width >> k)), faceH = int(std::max(1u, h.height >> k));
        const int hh = faceH * int(h.faces);
        const std::uint64_t expected = std::uint64_t(l.faceBytes(w, faceH)) * h.faces;
        if (length != expected || get<std::uint64_t>(b, at + 16) != expected)
            throw Error(name, field,
                        std::to_string(length) + " bytes, expected " + std::to_string(expected));
        if (offset % l.alignment() != 0)
            throw Error(name, field,
                        "offset " + std::to_string(offset) + " is not a multiple of " +
                            std::to_string(l.alignment()));
        checkRange(offset, length, b.size(), name, field);
        if (l.bc6h) {
            const auto* first = reinterpret_cast<const std::uint8_t*>(b.data()) + offset;
            t.blocks.emplace_back(first, first + length);
            if (limits.decodeBlocks)
                t.levels.push_back(decodeBC6HFaces(t.blocks.back(), w, faceH, int(h.faces)));
            continue;
        }
        Image image(w, hh, l.channels);
        if (l.half) {
            for (std::size_t i = 0; i < image.pixels.size(); ++i)
                image.pixels[i] = glm::unpackHalf1x16(get<std::uint16_t>(b, offset + 2 * i));
        } else {
            std::memcpy(image.pixels.data(), b.data() + offset, length);
        }
        t.levels.push_back(std::move(image));
    }
    return t;
}

Ktx2Texture readKtx2(const std::string& path, const Ktx2ReadLimits& limits) {
    // The file can hold no more than the values allowed plus its header, index, DFD and a
    // generous key/value block: bounded before a byte is read.
    const std::uint64_t maxBytes = limits.maxValues * 4 + (1u << 20);
    return parseKtx2(readRegularFile(path, maxBytes), path, limits);
}

std::string encodeKtx2(const Ktx2Texture& t, const std::string& name, const std::string& writer) {
    if (t.levels.empty()) throw Error(name, "levels", "no image to write");
    const Image& base = t.levels[0];
    const int faces = faceCount(t);
    if (base.channels < 1 || base.channels > 4)
        throw Error(name, "channels", std::to_string(base.channels) + " (1 to 4)");
    if (base.width < 1 || base.height % faces != 0 || (t.cube && base.height != 6 * base.width))
        throw Error(name, "size", t.cube ? "a cube level is N x 6N" : "an empty image");
    const Layout l{t.bc6h ? 3 : base.channels, t.halfFloat && !t.bc6h, t.bc6h};
    for (std::size_t k = 0; k < t.levels.size(); ++k) {
        const Image& m = t.levels[k];
        const int w = std::max(1, base.width >> k),
                  h = std::max(1, base.height / faces >> k) * faces;
        if (m.width != w || m.height != h || m.channels != base.channels ||
            m.pixels.size() != std::size_t(w) * h * std::size_t(base.channels))
            throw Error(name, "level " + std::to_string(k),
                        "expected " + std::to_string(w) + " x " + std::to_string(h) + " x " +
                            std::to_string(base.channels));
    }
    std::map<std::string, std::string> kv = t.keyValues;
    kv["KTXwriter"] = writer;
    if (!t.cube) kv["KTXorientation"] = "rd";
    std::string kvd; // std::map iterates keys in byte order, as the spec requires
    for (const auto& [key, value] : kv) {
        put(kvd, std::uint32_t(key.size() + 1 + value.size() + 1));
        kvd += key;
        kvd += '\0';
        kvd += value;
        kvd += '\0';
        kvd.resize(alignUp(kvd.size(), 4), '\0');
    }
    const std::vector<std::uint32_t> dfd = dataFormatDescriptor(l);
    const std::size_t dfdOffset = kHeaderBytes + kLevelIndexBytes * t.levels.size();
    const std::size_t kvdOffset = dfdOffset + dfd.size() * 4;
    // Level data, smallest level first, each at the layout's alignment.
    std::vector<std::size_t> offsets(t.levels.size()), sizes(t.levels.size());
    std::string data;
    std::size_t at = kvdOffset + kvd.size();
    for (std::size_t k = t.levels.size(); k-- > 0;) {
        const std::size_t aligned = alignUp(at, l.alignment());
        data.append(aligned - at, '\0');
        offsets[k] = aligned;
        const std::size_t before = data.size();
        if (l.bc6h) {
            // The caller's blocks when it has them (already encoded, and what it decoded),
            // else the levels encoded here.
            const std::vector<std::uint8_t> blocks =
                k < t.blocks.size() ? t.blocks[k] : encodeBC6HFaces(t.levels[k], faces);
            const int w = std::max(1, base.width >> k), fh = std::max(1, base.height / faces >> k);
            if (blocks.size() != std::size_t(faces) * bc6hBytes(w, fh))
                throw Error(name, "level " + std::to_string(k),
                            "holds " + std::to_string(blocks.size()) + " bytes of blocks, " +
                                std::to_string(std::size_t(faces) * bc6hBytes(w, fh)) +
                                " expected");
            data.append(reinterpret_cast<const char*>(blocks.data()), blocks.size());
        } else {
            appendLevel(data, t.levels[k], l.half);
        }
        sizes[k] = data.size() - before;
        at = aligned + (data.size() - before);
    }
    std::string out(reinterpret_cast<const char*>(kIdentifier), sizeof kIdentifier);
    for (std::uint32_t v :
         {l.vkFormat(), l.typeSize(), std::uint32_t(base.width), std::uint32_t(base.height / faces),
          0u, 0u, std::uint32_t(faces), std::uint32_t(t.levels.size()), 0u,
          std::uint32_t(dfdOffset), std::uint32_t(dfd.size() * 4), std::uint32_t(kvdOffset),
          std::uint32_t(kvd.size())})
        put(out, v);
    put(out, std::uint64_t(0));
    put(out, std::uint64_t(0));
    for (std::size_t k = 0; k < t.levels.size(); ++k) {
        const std::uint64_t bytes = sizes[k];
        put(out, std::uint64_t(offsets[k]));
        put(out, bytes);
        put(out, bytes);
    }
    for (std::uint32_t w : dfd)
        put(out, w);
    out += kvd;
    out += data;
    return out;
}

void writeKtx2(const std::string& path, const Ktx2Texture& texture, const std::string& writer) {
    writeFileAtomically(path, encodeKtx2(texture, path, writer));
}

void writeKtx2Cube(const std::string& path, const Image& stackedFaces) {
    writeKtx2(path, {.cube = true, .levels = {stackedFaces}});
}

void writeKtx2Image(const std::string& path, const Image& image) {
    writeKtx2(path, {.levels = {image}});
}

Image readKtx2Cube(const std::string& path, int faceRes, int channels) {
    Ktx2Texture t =
        readKtx2(path, {.width = faceRes, .height = faceRes, .faces = 6, .channels = channels});
    return std::move(t.levels[0]);
}

Image readKtx2Image(const std::string& path, int width, int height, int channels) {
    Ktx2Texture t =
        readKtx2(path, {.width = width, .height = height, .faces = 1, .channels = channels});
    return std::move(t.levels[0]);
}

} // namespace specula
