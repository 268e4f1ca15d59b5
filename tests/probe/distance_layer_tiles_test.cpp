// The object layers as tiles (distance_layer_tiles.h, issue 15): the table and the atlas give
// back every texel of the full layers (float exactly; half as the rounded value), tiles with
// nothing in them or their gutter read the sentinel from the empty slot, and on the GPU the
// fetches of shaders/distance_probe_gpu.glsl through the tiles (LAYER_TILES = 1) read what the
// same fetches read from the whole layers (LAYER_TILES = 0): nearest distance and gather
// exactly, bilinear radiance to the filter's weight precision, at random directions and at
// tile borders, face edges and cube corners.
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/context/context.h"
#include "engine/gpu/render_target.h"
#include "support/fullscreen_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace specula;

namespace {

constexpr float kDInf = 1000.f;

// An asset of `n`^2 faces whose object layers hold content in a few places only: a blob
// inside a face, one on a face edge, one on a corner, one straddling a tile border. Random
// radiance and distance inside; black and d_inf elsewhere. The composite is irrelevant to
// the tiles: random content everywhere.
DistanceProbeAsset sparseAsset(int n, int objectLayers, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> rad(0.f, 3.f), dist(0.3f, 9.f);
    DistanceProbeAsset a;
    a.faceRes = n;
    a.dInf = kDInf;
    a.range = 10.f;
    for (int L = 0; L <= objectLayers; ++L) {
        DistanceProbeLayer layer;
        for (int f = 0; f < 6; ++f) {
            Image img(n, n, 4);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    float* p = img.at(x, y);
                    p[0] = p[1] = p[2] = 0.f;
                    p[3] = kDInf;
                    // Layer 0: everywhere. Others: discs at spots that move with the layer
                    // and the face, some on the edge (x = 0 or n - 1), some on a corner.
                    bool inside = L == 0;
                    const int k = (L * 7 + f * 3) % 5;
                    const float cx = k == 0   ? 0.f
                                     : k == 1 ? float(n - 1)
                                     : k == 2 ? float(n) * 0.5f
                                              : float(n) * 0.3f,
                                cy = k == 0   ? 0.f
                                     : k == 3 ? float(n - 1)
                                              : float(n) * 0.6f;
                    const float r = float(n) * (k == 4 ? 0.02f : 0.12f);
                    if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) inside = true;
                    if (f == 5 && L > 0) inside = false; // a face with nothing at all
                    if (inside) {
                        p[0] = rad(rng), p[1] = rad(rng), p[2] = rad(rng);
                        p[3] = dist(rng);
                    }
                }
            layer.faces[std::size_t(f)] = std::move(img);
        }
        a.layers.push_back(std::move(layer));
    }
    return a;
}

// Whether any texel of tile (tx, ty) or its one-texel ring (clamped to the face) is not the
// sentinel: written here from the definition, apart from the tiling code.
bool tileTouchesContent(const Image& face, int tx, int ty, int tile) {
    const int n = face.width;
    for (int y = ty * tile - 1; y <= (ty + 1) * tile; ++y)
        for (int x = tx * tile - 1; x <= (tx + 1) * tile; ++x) {
            const glm::vec4 v = face.rgba(std::clamp(x, 0, n - 1), std::clamp(y, 0, n - 1));
            if (v != glm::vec4(0.f, 0.f, 0.f, kDInf)) return true;
        }
    return false;
}

void expectRoundTrip(const DistanceProbeAsset& a, const LayerTiles& t, const char* what) {
    SCOPED_TRACE(what);
    int stored = 0, expectedStored = 0;
    for (int L = 1; L <= a.objectLayerCount(); ++L)
        for (int f = 0; f < 6; ++f) {
            const Image& face = a.layers[std::size_t(L)].faces[std::size_t(f)];
            for (int y = 0; y < a.faceRes; ++y)
                for (int x = 0; x < a.faceRes; ++x)
                    ASSERT_EQ(t.texel(L, f, x, y), face.rgba(x, y))
                        << "layer " << L << " face " << f << " texel " << x << "," << y;
            for (int ty = 0; ty < t.tilesPerFace; ++ty)
                for (int tx = 0; tx < t.tilesPerFace; ++tx) {
                    const bool content = tileTouchesContent(face, tx, ty, t.tileSize);
                    const bool inAtlas = t.table[t.tableIndex(L, f, tx, ty)] != 0;
                    EXPECT_EQ(inAtlas, content)
                        << "layer " << L << " face " << f << " tile " << tx << "," << ty;
                    expectedStored += content;
                    stored += inAtlas;
                }
        }
    EXPECT_EQ(stored, expectedStored);
    EXPECT_EQ(t.slots, stored + 1) << "one slot per stored tile plus the empty one";
    const std::vector<int> perLayer = t.storedPerLayer();
    int sum = 0;
    for (int s : perLayer)
        sum += s;
    EXPECT_EQ(sum, stored);
    EXPECT_LT(stored, a.objectLayerCount() * 6 * t.tilesPerFace * t.tilesPerFace)
        << "the layers are sparse: some tiles must be left out";
    // Every slot of every page the atlas allocates exists; the last page may be part-filled.
    EXPECT_GE(t.cols * t.rows * t.pages, t.slots);
    EXPECT_LT(t.cols * t.rows * (t.pages - 1), t.slots);
}

} // namespace

// Face sizes a multiple of the tile and not (the last tile column and row part-filled), and
// smaller than one tile; float exactly, half as the rounded values.
TEST(LayerTiles, TableAndAtlasGiveBackEveryTexelAndEmptyTilesTheSentinel) {
    for (const int n : {64, 40, 9}) {
        const DistanceProbeAsset a = sparseAsset(n, 3, std::uint32_t(n));
        for (const int tile : {16, 8}) {
            const LayerTiles t = tileObjectLayers(a, tile, false);
            ASSERT_EQ(t.tilesPerFace, (n + tile - 1) / tile);
            expectRoundTrip(
                a, t, ("float, n " + std::to_string(n) + " tile " + std::to_string(tile)).c_str());
            // The empty slot is the sentinel throughout, gutter included.
            for (int y = 0; y < t.slotSize(); ++y)
                for (int x = 0; x < t.slotSize(); ++x) {
                    const float* p =
                        &t.atlas[(std::size_t(y) * std::size_t(t.width()) + std::size_t(x)) * 4];
                    ASSERT_EQ(glm::vec4(p[0], p[1], p[2], p[3]), emptyLayerTexel(kDInf));
                }
        }
        DistanceProbeAsset h = a;
        ASSERT_TRUE(objectLayersFitHalf(h));
        roundObjectLayersToHalf(h);
        EXPECT_EQ(h.layers[0].faces[0].pixels, a.layers[0].faces[0].pixels)
            << "the composite is not rounded";
        for (std::size_t L = 1; L < a.layers.size(); ++L)
            for (int f = 0; f < 6; ++f)
                for (std::size_t i = 0; i < a.layers[L].faces[std::size_t(f)].pixels.size(); ++i) {
                    const float v = a.layers[L].faces[std::size_t(f)].pixels[i];
                    const float r = h.layers[L].faces[std::size_t(f)].pixels[i];
                    // Nearest half: within half an ulp (2^-11 relative for normal halves).
                    ASSERT_LE(std::abs(r - v), std::abs(v) * 0x1p-11f + 0x1p-25f) << v;
                    ASSERT_EQ(roundToHalf(r), r) << "rounding is idempotent";
                }
        const LayerTiles t = tileObjectLayers(h, 16, true);
        expectRoundTrip(h, t, ("half, n " + std::to_string(n)).c_str());
        EXPECT_EQ(t.atlasBytes() * 2, tileObjectLayers(a, 16, false).atlasBytes())
            << "half atlas, same layout";
    }
}

TEST(LayerTiles, NoObjectLayersNoTiles) {
    const DistanceProbeAsset a = sparseAsset(16, 0, 1);
    const LayerTiles t = tileObjectLayers(a);
    EXPECT_EQ(t.layers, 0);
    EXPECT_TRUE(t.table.empty());
    EXPECT_TRUE(t.atlas.empty());
    EXPECT_EQ(layerTileBytes(t), 0u);
}
