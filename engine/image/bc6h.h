#pragma once
// BC6H, unsigned (BPTC float: VK_FORMAT_BC6H_UFLOAT_BLOCK, GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT):
// 16 bytes per 4x4 block of RGB half floats, 8 bits per texel against 64 for RGBA16F. The
// layout a GPU samples directly; the codec knows nothing of what the texels mean.
//
// The decoder reads every mode of the format (fourteen, one or two regions, transformed
// endpoints) bit-exactly as the Khronos Data Format specification decodes them: the runtime's
// CPU twins read compressed probes through it. The encoder (bc6h_encode.cpp) fits the
// one-region 10-bit mode and the two-region modes on the block's two best partitions in the
// half floats' bit space (where a step is a constant share of the value, as the eye and an
// HDR error measure weigh it) and keeps the better; it is ours, so a bake's bytes are the same
// on every machine, whatever its GL driver.
#include "engine/image/image.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace specula {

inline constexpr std::size_t kBc6hBlockBytes = 16;
// The largest finite half float (65504) as bits: what a texel above it is clamped to.
inline constexpr std::uint16_t kMaxHalfBits = 0x7BFF;

// Bytes of the blocks of a width x height image (partial blocks count whole).
std::size_t bc6hBytes(int width, int height);

// Blocks in row order of the first three channels of `image` (any size: a partial block
// repeats the image's last column and row). Negative and NaN values are stored as 0, values
// above 65504 and infinities as 65504.
std::vector<std::uint8_t> encodeBC6H(const Image& image);

// Half-float bits, three per texel, rows top to bottom, of `blocks` (bc6hBytes(width,
// height) of them, else std::invalid_argument). A block of a reserved mode decodes to black,
// as GPUs decode it.
std::vector<std::uint16_t> decodeBC6HHalf(std::span<const std::uint8_t> blocks, int width,
                                          int height);
// The same as a 3-channel float image.
Image decodeBC6H(std::span<const std::uint8_t> blocks, int width, int height);

// A level of `faces` faces stacked top to bottom (width x faces * faceHeight, as KTX2 cube
// levels are held in memory): each face encoded on its own, so a face whose side is no multiple
// of 4 has padded blocks of its own, and the blocks concatenated in face order (what KTX2 stores
// and glCompressedTexSubImage3D uploads as `faces` array layers).
std::vector<std::uint8_t> encodeBC6HFaces(const Image& stacked, int faces);
Image decodeBC6HFaces(std::span<const std::uint8_t> blocks, int width, int faceHeight, int faces);

} // namespace specula
