#pragma once
// Mip levels of a light-field atlas, for the glossy lookup (shaders/lightfield_glossy.glsl.h):
// level k of a slab's layer holds every camera image box-filtered to RES / 2^k texels a side,
// each camera in its own tile, so a filter at level k never mixes two cameras. Made from the
// cooked level 0 when the first rough reflector needs them (a mirror-only scene never pays
// for them), once, deterministically: the store uploads exactly these bytes and the CPU twin
// decodes exactly these bytes, so the two read the same texels.
//
// Filter: each level is the 2x2 box average of the one above in linear light, carried in
// float from level 0 (so 8-bit rounding does not pile up level over level), then encoded as
// level 0 is: sRGB 8-bit codes, or BC1 blocks of them.
#include "components/reflection_probe/lightfield/lightfield_asset.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace specula {

// The deepest level whose camera tiles are whole texels (RES / 2^k an integer) and, for BC1,
// whole 4x4 blocks (RES / 2^k a multiple of 4): RES 64 -> 6 (BC1: 4), RES 48 -> 4 (BC1: 2).
int lightFieldMaxLevel(int res, LightFieldCompression c);

struct LightFieldMips {
    // levels[k - 1][slab]: level k (1 .. maxLevel) of the slab's layer, (atlasSize >> k)^2
    // texels, encoded as level 0 is (rows top to bottom: RGB8 sRGB codes, or BC1 blocks).
    std::vector<std::array<std::vector<std::uint8_t>, 6>> levels;

    int maxLevel() const { return int(levels.size()); }
    // Texture memory of the levels beyond 0 (RGB8 is held as RGBA8, 4 bytes a texel).
    std::size_t gpuBytes(int atlasSize, LightFieldCompression c) const;
};

LightFieldMips buildLightFieldMips(const LightFieldAsset& asset);
// The same from the six layers' level 0 as RGB8 sRGB codes (BC1 already decoded), atlas side
// cameras * res: what the CPU twin holds.
LightFieldMips buildLightFieldMips(const std::array<std::vector<std::uint8_t>, 6>& codes,
                                   int cameras, int res, LightFieldCompression c);

} // namespace specula
