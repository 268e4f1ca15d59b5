#pragma once
// Khronos KTX 2.0 files of linear float images: the container every cooked probe texture is
// stored in, read by the runtime without any image library. What is written and accepted:
//  - vkFormat R/RG/RGB/RGBA in 32-bit float (100, 103, 106, 109) or 16-bit half float (76,
//    83, 90, 97), or BC6H unsigned float blocks (131, engine/image/bc6h.h); no supercompression;
//  - a 2D image (faceCount 1) or a cube map (faceCount 6, faces +X -X +Y -Y +Z -Z), each with
//    one or more mip levels;
//  - a Data Format Descriptor of one basic block (RGBSDA colour model, BT.709 primaries,
//    linear transfer, one float sample per channel; for BC6H the BC6H model, a 4x4 texel block
//    of 16 bytes, one float sample of 128 bits) and key/value data (KTXwriter,
//    KTXorientation "rd" for 2D images, any of the caller's keys).
// In memory a cube level is one Image of N x 6N, the faces stacked top to bottom in the order
// above: exactly the level's bytes in the file, so upload is a copy. Row 0 is the top row.
// Every read is checked against the file's length and the caller's limits before any pixel
// is allocated; a file that lies (an offset past its end, a level of the wrong length, a DFD
// that does not describe the vkFormat) is refused with an Error naming the file and field.
#include "engine/image/image.h"

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace specula {

struct Ktx2Texture {
    bool cube = false;
    bool halfFloat = false; // stored as 16-bit half floats (read: what the file held)
    // Stored as BC6H blocks: written from `blocks` where it has the level (the caller's
    // encoding, which must be the level's size in blocks), else by encoding `levels` (RGB; a
    // fourth channel is dropped); read as `blocks` plus, unless Ktx2ReadLimits::decodeBlocks
    // is off, `levels` decoded (RGB). `levels` gives the sizes either way.
    bool bc6h = false;
    // Level 0 first; each halves the one before (at least 1), a cube's stacked as N x 6N.
    std::vector<Image> levels{};
    std::map<std::string, std::string> keyValues{}; // KTXwriter etc.; values without their NUL
    // BC6H files, read: each level's blocks as stored (faces in order, a face's blocks row by
    // row), what glCompressedTexSubImage uploads.
    std::vector<std::vector<std::uint8_t>> blocks{};
};

struct Ktx2ReadLimits {
    // width x height x faces x channels over all levels; the default admits a face-res 8192
    // cube with its mips.
    std::uint64_t maxValues = 1ull << 31;
    // When > 0, level 0 must be exactly this (a cube's face size for width and height).
    int width = 0;
    int height = 0;
    int faces = 0;    // when > 0: 1 (2D) or 6 (cube)
    int channels = 0; // when > 0: exactly this many
    bool decodeBlocks = true; // BC6H: decode the blocks into `levels` too
};

// The 12 bytes every KTX 2.0 file begins with.
inline constexpr unsigned char kKtx2Identifier[12] = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                                      '0',  0xBB, '\r', '\n', 0x1A, '\n'};

// Throws Error(path, field, why) for a file that cannot be read or is not what is described
// above; field is the header field, "dfd", "kvd" or "level N".
Ktx2Texture readKtx2(const std::string& path, const Ktx2ReadLimits& limits = {});
// Parses a whole file already in memory; `name` is what errors call it.
Ktx2Texture parseKtx2(const std::string& bytes, const std::string& name,
                      const Ktx2ReadLimits& limits = {});

// The file's bytes; KTXwriter is `writer`. Throws Error(name, ...) for levels that are not a
// valid chain (sizes, channel counts, a cube level not N x 6N).
std::string encodeKtx2(const Ktx2Texture& texture, const std::string& name,
                       const std::string& writer = "Specula");
// Writes atomically (writeFileAtomically): a full disk never leaves a partial file.
void writeKtx2(const std::string& path, const Ktx2Texture& texture,
               const std::string& writer = "Specula");

// The common cases: one level, 32-bit float.
void writeKtx2Cube(const std::string& path, const Image& stackedFaces);
void writeKtx2Image(const std::string& path, const Image& image);
// Level 0 of a cube of faceRes (an N x 6N Image) / of a 2D image of exactly width x height
// (0: any size); any channel count unless given.
Image readKtx2Cube(const std::string& path, int faceRes, int channels = 0);
Image readKtx2Image(const std::string& path, int width = 0, int height = 0, int channels = 0);

} // namespace specula
