#include "distance_layer_tiles.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

namespace specula {

namespace {

// Largest atlas side: well under GL 4.5's least MAX_TEXTURE_SIZE (16384), so pages stay small.
constexpr int kMaxAtlasSide = 4096;

// Face texel (x, y), clamped to the face as the full layer's sampler clamps.
glm::vec4 clampedTexel(const Image& face, int x, int y) {
    const int n = face.width;
    return face.rgba(std::clamp(x, 0, n - 1), std::clamp(y, 0, n - 1));
}

// Whether tile (tx, ty) of `face` or its gutter holds anything but the sentinel: only then can
// a fetch inside the tile read something the empty slot does not hold.
bool tileHasContent(const Image& face, int tx, int ty, int tileSize, glm::vec4 empty) {
    const int x0 = tx * tileSize - 1, y0 = ty * tileSize - 1;
    for (int y = y0; y < y0 + tileSize + 2; ++y)
        for (int x = x0; x < x0 + tileSize + 2; ++x)
            if (clampedTexel(face, x, y) != empty) return true;
    return false;
}

} // namespace

glm::vec4 emptyLayerTexel(float dInf) {
    return glm::vec4(0.f, 0.f, 0.f, dInf);
}

float roundToHalf(float v) {
    return glm::unpackHalf1x16(glm::packHalf1x16(v));
}

namespace {

// Radiance is at most kMaxRadiance (the largest half) and distances at most d_inf, as the
// reader checks; d_inf must round to a finite half. Distances below half's smallest normal
// (2^-14 m: a scene modelled in kilometres, or scaled down) would lose their relative
// precision as subnormals, and the layer order with it: such layers stay float.
bool layersFitHalf(const DistanceProbeAsset& asset, std::size_t first) {
    if (!std::isfinite(roundToHalf(asset.dInf))) return false;
    for (std::size_t L = first; L < asset.layers.size(); ++L)
        for (const Image& face : asset.layers[L].faces)
            for (std::size_t i = 3; i < face.pixels.size(); i += std::size_t(face.channels))
                if (face.pixels[i] < 0x1p-14f) return false; // RGBA: distance in alpha
    return true;
}

void roundLayersToHalf(DistanceProbeAsset& asset, std::size_t first) {
    for (std::size_t L = first; L < asset.layers.size(); ++L)
        for (Image& face : asset.layers[L].faces)
            for (float& v : face.pixels)
                v = roundToHalf(v);
}

} // namespace

bool objectLayersFitHalf(const DistanceProbeAsset& asset) {
    return layersFitHalf(asset, 1);
}

bool allLayersFitHalf(const DistanceProbeAsset& asset) {
    return layersFitHalf(asset, 0);
}

void roundObjectLayersToHalf(DistanceProbeAsset& asset) {
    roundLayersToHalf(asset, 1);
}

void roundAllLayersToHalf(DistanceProbeAsset& asset) {
    roundLayersToHalf(asset, 0);
}

LayerTiles tileObjectLayers(const DistanceProbeAsset& asset, int tileSize, bool half) {
    LayerTiles t;
    t.faceRes = asset.faceRes;
    t.tileSize = tileSize;
    t.tilesPerFace = (asset.faceRes + tileSize - 1) / tileSize;
    t.layers = asset.objectLayerCount();
    t.half = half;
    const int tpf = t.tilesPerFace;
    t.table.assign(std::size_t(t.layers) * 6 * std::size_t(tpf) * std::size_t(tpf), 0);
    // The sentinel as the atlas will hold it (d_inf rounded when stored as half).
    const glm::vec4 empty = emptyLayerTexel(half ? roundToHalf(asset.dInf) : asset.dInf);

    // Slots: 0 the empty tile, then the tiles with content in layer, face, row order.
    struct Source {
        const Image* face;
        int tx, ty;
    };
    std::vector<Source> sources{{nullptr, 0, 0}};
    for (int L = 1; L <= t.layers; ++L)
        for (int f = 0; f < 6; ++f) {
            const Image& face = asset.layers[std::size_t(L)].faces[std::size_t(f)];
            for (int ty = 0; ty < tpf; ++ty)
                for (int tx = 0; tx < tpf; ++tx)
                    if (tileHasContent(face, tx, ty, tileSize, empty)) {
                        t.table[t.tableIndex(L, f, tx, ty)] = std::int32_t(sources.size());
                        sources.push_back({&face, tx, ty});
                    }
        }
    if (t.layers == 0) return t;

    t.slots = int(sources.size());
    const int s = t.slotSize(), maxSlots = std::max(1, kMaxAtlasSide / s);
    t.cols = std::min(int(std::ceil(std::sqrt(double(t.slots)))), maxSlots);
    t.rows = std::min((t.slots + t.cols - 1) / t.cols, maxSlots);
    t.pages = (t.slots + t.cols * t.rows - 1) / (t.cols * t.rows);
    const std::size_t w = std::size_t(t.width()), h = std::size_t(t.height());
    t.atlas.assign(w * h * std::size_t(t.pages) * 4, 0.f);
    for (int slot = 0; slot < t.slots; ++slot) {
        const int page = slot / (t.cols * t.rows), inPage = slot % (t.cols * t.rows);
        const int ox = inPage % t.cols * s, oy = inPage / t.cols * s;
        const Source& src = sources[std::size_t(slot)];
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const glm::vec4 v = src.face ? clampedTexel(*src.face, src.tx * tileSize + i - 1,
                                                            src.ty * tileSize + j - 1)
                                             : empty;
                float* p = &t.atlas[((std::size_t(page) * h + std::size_t(oy + j)) * w +
                                     std::size_t(ox + i)) *
                                    4];
                for (int c = 0; c < 4; ++c)
                    p[c] = v[c];
            }
    }
    return t;
}

glm::ivec3 LayerTiles::slotOrigin(int slot) const {
    const int s = slotSize(), inPage = slot % (cols * rows);
    return glm::ivec3(inPage % cols * s, inPage / cols * s, slot / (cols * rows));
}

std::vector<std::int16_t> LayerTiles::tableOrigins() const {
    std::vector<std::int16_t> texels;
    texels.reserve(table.size() * 4);
    for (const std::int32_t slot : table) {
        const glm::ivec3 o = slotOrigin(slot);
        for (const int v : {o.x, o.y, o.z, 0})
            texels.push_back(std::int16_t(v));
    }
    return texels;
}

glm::vec4 LayerTiles::texel(int layer, int face, int x, int y) const {
    const int tx = x / tileSize, ty = y / tileSize;
    const glm::ivec3 o = slotOrigin(table[tableIndex(layer, face, tx, ty)]);
    const int ax = o.x + x - tx * tileSize + 1, ay = o.y + y - ty * tileSize + 1, page = o.z;
    const float* p = &atlas[((std::size_t(page) * std::size_t(height()) + std::size_t(ay)) *
                                 std::size_t(width()) +
                             std::size_t(ax)) *
                            4];
    return glm::vec4(p[0], p[1], p[2], p[3]);
}

std::vector<int> LayerTiles::storedPerLayer() const {
    std::vector<int> stored(std::size_t(layers), 0);
    const std::size_t perLayer = 6 * std::size_t(tilesPerFace) * std::size_t(tilesPerFace);
    for (std::size_t i = 0; i < table.size(); ++i)
        if (table[i] != 0) ++stored[i / perLayer];
    return stored;
}

} // namespace specula
