#pragma once
// The object layers (1..) of a distance probe as tiles: each face cut in tileSize^2 tiles, a
// tile stored in an atlas only when its texels or its one-texel ring hold content, and a table
// from every tile to its atlas slot. The ring (the gutter) holds the face's neighbouring texels,
// clamped at the face edge, so a bilinear fetch or gather anywhere inside a tile reads the very
// texels the full face would. Slot 0 is the empty tile: every texel the sentinel an object
// layer holds where it sees nothing (black, distance d_inf), so an empty tile reads what the
// full layer read there. The composite (layer 0) is not tiled: every direction sees something
// or the sky, and the glossy chain reads it whole. Plain CPU data; distance_textures.h uploads
// it and shaders/distance_probe_gpu.glsl (LAYER_TILES) reads it.
#include "components/reflection_probe/distance/distance_probe_asset.h"

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace specula {

// Texels per tile side. Measured on the room's 13 object layers (half-float atlas + table):
// 128^2 faces 8: 1.24, 16: 1.06, 32: 1.38 MiB; 256^2 faces 8: 4.65, 16: 3.84, 32: 3.72,
// 64: 5.19 MiB. Smaller tiles follow the objects' outlines closer but pay more gutter; 16 is
// best or within 3% of it at both sizes.
inline constexpr int kLayerTileSize = 16;

struct LayerTiles {
    int faceRes = 0;
    int tileSize = 0;
    int tilesPerFace = 0;              // tiles along a face side: ceil(faceRes / tileSize)
    int layers = 0;                    // object layers tiled (the asset's layers 1..)
    int cols = 0, rows = 0, pages = 0; // atlas slots per page row, slot rows per page, pages
    int slots = 0;                     // slots in use, the empty one (0) included
    bool half = false;                 // atlas texels are half floats (RGBA16F)
    // Slot of tile (tx, ty) of face f of object layer L (1..): table[tableIndex(L, f, tx, ty)].
    std::vector<std::int32_t> table;
    // RGBA texels, pages of width() x height(), row-major, page after page.
    std::vector<float> atlas;

    int slotSize() const { return tileSize + 2; }
    // The atlas texel where slot `slot`'s tile starts (gutter included) and its page: what the
    // GPU table holds per tile, so the shader reads an origin instead of dividing a slot index
    // (integer division by a uniform is a long sequence on GPUs and in llvmpipe alike).
    glm::ivec3 slotOrigin(int slot) const;
    int width() const { return cols * slotSize(); }
    int height() const { return rows * slotSize(); }
    std::size_t tableIndex(int layer, int face, int tx, int ty) const {
        return ((std::size_t(layer - 1) * 6 + std::size_t(face)) * std::size_t(tilesPerFace) +
                std::size_t(ty)) *
                   std::size_t(tilesPerFace) +
               std::size_t(tx);
    }
    // Texel (x, y) (the face's, 0..faceRes-1) of face f of object layer L, read through the
    // table and the atlas as the shader reads it.
    glm::vec4 texel(int layer, int face, int x, int y) const;
    // Tiles stored per object layer (index L - 1) out of 6 tilesPerFace^2.
    std::vector<int> storedPerLayer() const;

    std::size_t atlasBytes() const {
        return std::size_t(width()) * std::size_t(height()) * std::size_t(pages) * (half ? 8 : 16);
    }
    // The GPU table: an RGBA16I origin (slotOrigin) per tile.
    std::size_t tableBytes() const { return table.size() * 4 * sizeof(std::int16_t); }
    // slotOrigin of every table entry, in table order, as the GPU table's RGBA16I texels.
    std::vector<std::int16_t> tableOrigins() const;
};

// What an object layer holds where it sees nothing.
glm::vec4 emptyLayerTexel(float dInf);

// Tiles the asset's object layers (none: layers = 0, no slots). `half`: the atlas will be
// stored as half floats; its values must then already be half-representable
// (roundObjectLayersToHalf), so the atlas holds exactly the asset's values.
LayerTiles tileObjectLayers(const DistanceProbeAsset& asset, int tileSize = kLayerTileSize,
                            bool half = false);

// Whether the object layers can be stored as half floats: every value (radiance <=
// kMaxRadiance, distances <= d_inf) within half's range, and no distance below half's
// smallest normal (2^-14).
bool objectLayersFitHalf(const DistanceProbeAsset& asset);
// The same for every layer, the composite included.
bool allLayersFitHalf(const DistanceProbeAsset& asset);
// Rounds every texel of the object layers to the nearest half float, so the CPU twin reads
// what an RGBA16F atlas holds. The composite and the sky stay as they are.
void roundObjectLayersToHalf(DistanceProbeAsset& asset);
// The same for every layer, the composite included (what an RGBA16F composite would hold).
void roundAllLayersToHalf(DistanceProbeAsset& asset);
float roundToHalf(float v);

} // namespace specula
