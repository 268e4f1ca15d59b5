#pragma once
// BC1 (DXT1, S3TC) block compression of 8-bit RGB images: 8 bytes per 4x4 block, two RGB565
// endpoints and sixteen 2-bit palette indices. The layout GL_COMPRESSED_*_S3TC_DXT1_EXT
// uploads; the codec knows nothing of what the texels mean.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace specula {

// Encodes an RGB8 image (width and height multiples of 4; 3 bytes per texel, rows top to
// bottom) into blocks in row order. Always the four-colour mode (c0 > c1), or c0 == c1 with
// every index 0 for a block whose colours all round to one 565 value.
std::vector<std::uint8_t> encodeBC1(const std::uint8_t* rgb, int width, int height);

// Decodes BC1 blocks back to RGB8, as the GPU's decoder does (to within rounding).
std::vector<std::uint8_t> decodeBC1(const std::uint8_t* blocks, int width, int height);

// The first block, counted from 0, that a GPU cannot decode to an opaque colour: with
// c0 <= c1 a block is in BC1's three-colour mode, where index 3 means transparent black.
// encodeBC1 never writes one; random or damaged bytes hit it in about half their blocks.
// nullopt when every whole block of `blocks` decodes to colours.
std::optional<std::size_t> firstUndecodableBC1Block(std::span<const std::uint8_t> blocks);

} // namespace specula
