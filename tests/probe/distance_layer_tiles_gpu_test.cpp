// The object layers' tiles on the GPU (issue 15): shaders/distance_probe_gpu.glsl's fetches
// through the tile table and atlas (LAYER_TILES = 1) against the same fetches over the whole
// layers in one array (LAYER_TILES = 0, as before tiling), and the store's byte count against
// the real sizes of the textures it holds in layered mode.
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/context/context.h"
#include "engine/gpu/render_target.h"
#include "engine/math/cube_face.h"
#include "probe_fixture.h"
#include "support/fullscreen_pass.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace specula;

namespace {

constexpr float kDInf = 1000.f;

constexpr const char* kFrag = R"(
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_probe_gpu.glsl"
uniform sampler2D uQueries; // xyz direction, w object layer
uniform int uOutput;
out vec4 fragColor;
void main() {
    vec4 q = texelFetch(uQueries, ivec2(gl_FragCoord.xy), 0);
    int layer = int(q.w);
    fragColor = uOutput == 0 ? vec4(fetchRadiance(layer, q.xyz), fetchDistance(layer, q.xyz))
                             : fetchDistanceGather(layer, q.xyz);
}
)";

// Object layers with smooth-ish random content in scattered tiles: a random subset of each
// face's 8 x 8 blocks holds random radiance and distance, the rest the sentinel.
DistanceProbeAsset patchyAsset(int n, int objectLayers) {
    std::mt19937 rng(std::uint32_t(n * 31 + objectLayers));
    std::uniform_real_distribution<float> rad(0.f, 4.f), dist(0.5f, 8.f), coin(0.f, 1.f);
    DistanceProbeAsset a;
    a.faceRes = n;
    a.dInf = kDInf;
    for (int L = 0; L <= objectLayers; ++L) {
        DistanceProbeLayer layer;
        for (int f = 0; f < 6; ++f) {
            Image img(n, n, 4);
            const int blocks = (n + 7) / 8;
            std::vector<char> on(std::size_t(blocks * blocks));
            for (char& b : on)
                b = L == 0 || coin(rng) < 0.06f;
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    float* p = img.at(x, y);
                    const bool inside = on[std::size_t((y / 8) * blocks + x / 8)] != 0;
                    p[0] = inside ? rad(rng) : 0.f;
                    p[1] = inside ? rad(rng) : 0.f;
                    p[2] = inside ? rad(rng) : 0.f;
                    p[3] = inside ? dist(rng) : kDInf;
                }
            layer.faces[std::size_t(f)] = std::move(img);
        }
        a.layers.push_back(std::move(layer));
    }
    return a;
}

// Queries: random directions, and points of random faces placed on and beside tile borders,
// on face edges and at cube corners (as directions through them).
std::vector<glm::vec4> queriesFor(int n, int tile, int objectLayers, int count) {
    std::mt19937 rng(std::uint32_t(n + tile));
    std::uniform_real_distribution<float> u(-1.f, 1.f), t01(0.f, 1.f);
    std::uniform_int_distribution<int> face(0, 5), layer(1, objectLayers);
    const int tiles = (n + tile - 1) / tile;
    std::uniform_int_distribution<int> border(0, tiles);
    const float offsets[] = {0.f, 0.25f, -0.25f, 0.5f, -0.5f, 0.75f, -0.75f, 1.3f, -1.3f};
    auto q = std::vector<glm::vec4>(std::size_t(count));
    for (int k = 0; k < count; ++k) {
        glm::vec3 d(u(rng), u(rng), u(rng));
        const int kind = k % 4;
        if (kind != 0) {
            // Texel-space coordinates at a tile border (or a face edge: border 0 or tiles).
            auto nearBorder = [&] {
                const float o = offsets[std::size_t(k / 4) % std::size(offsets)];
                return std::clamp(float(std::min(border(rng) * tile, n)) + o, 0.f, float(n));
            };
            glm::vec2 p(nearBorder(), t01(rng) * float(n));
            if (kind == 2) p = glm::vec2(p.y, p.x);
            if (kind == 3) p = glm::vec2(nearBorder(), nearBorder()); // tile or cube corner
            d = glsl::cubeFaceDirection(face(rng), p / float(n));
        }
        q[std::size_t(k)] = glm::vec4(d, float(layer(rng)));
    }
    return q;
}

struct FetchImages {
    Image values, gathers; // row 0 at the top
};

FetchImages runFetches(gpu::Program& prog, const gpu::Texture& queries, int w, int h,
                       const glsl::DistanceParamsBlock& block, const gpu::Texture& layers,
                       const LayerTileTextures* tiles, const LayerTiles* grid) {
    const gpu::VertexArray vao = gpu::VertexArray::create();
    gpu::RenderTarget target(w, h);
    gpu::UniformBuffer<glsl::DistanceParamsBlock> params;
    params.upload(block);
    FetchImages out;
    for (int pass = 0; pass < 2; ++pass) {
        (pass == 0 ? out.values : out.gathers) = test::drawFullscreen(target, prog, vao, [&] {
            glBindTextureUnit(1, layers.id());
            glBindTextureUnit(4, queries.id());
            prog.setUniform("uLayers", 1);
            prog.setUniform("uQueries", 4);
            prog.setUniform("uOutput", pass);
            if (tiles) {
                glBindTextureUnit(5, tiles->atlas.id());
                glBindTextureUnit(6, tiles->table.id());
                prog.setUniform("uTileAtlas", 5);
                prog.setUniform("uTileTable", 6);
                prog.setUniform("uTileGrid", glm::ivec2(grid->tileSize, grid->tilesPerFace));
            }
            params.bind(glsl::kDistanceParamsBinding);
        });
    }
    return out;
}

} // namespace

// Float and half atlases, face sizes a multiple of the tile and not.
TEST(LayerTilesGpu, FetchesThroughTheTilesReadWhatTheWholeLayersRead) {
    const auto context = gpu::GlContext::createHeadless();
    gpu::Program whole = test::buildFullscreenProgram("whole", kFrag, {"LAYER_TILES=0"});
    gpu::Program tiled = test::buildFullscreenProgram("tiled", kFrag, {"LAYER_TILES=1"});
    constexpr int kW = 128, kH = 64, kLayers = 3;
    struct Case {
        int n;
        bool half;
    };
    for (const Case c : {Case{64, false}, Case{40, false}, Case{64, true}}) {
        SCOPED_TRACE(std::to_string(c.n) + (c.half ? " half" : " float"));
        DistanceProbeAsset a = patchyAsset(c.n, kLayers);
        if (c.half) roundObjectLayersToHalf(a);
        const LayerTiles t = tileObjectLayers(a, kLayerTileSize, c.half);
        const LayerTileTextures tiles = uploadLayerTiles(t);
        const gpu::Texture all = createCubeArray(c.n, kLayers + 1);
        for (int L = 0; L <= kLayers; ++L)
            uploadCube(all, L, a.layers[std::size_t(L)]);
        const gpu::Texture composite = createCubeArray(c.n, 1);
        uploadCube(composite, 0, a.layers[0]);

        const std::vector<glm::vec4> q = queriesFor(c.n, kLayerTileSize, kLayers, kW * kH);
        gpu::Texture queries = gpu::Texture::create(GL_TEXTURE_2D);
        glTextureStorage2D(queries.id(), 1, GL_RGBA32F, kW, kH);
        glTextureSubImage2D(queries.id(), 0, 0, 0, kW, kH, GL_RGBA, GL_FLOAT, q.data());
        glsl::DistanceParamsBlock block{};
        block.params.faceRes = c.n;
        block.params.dInf = kDInf;
        const FetchImages want = runFetches(whole, queries, kW, kH, block, all, nullptr, nullptr);
        const FetchImages got = runFetches(tiled, queries, kW, kH, block, composite, &tiles, &t);

        long distanceSame = 0, gatherSame = 0, gatherUnexplained = 0, radianceWithin = 0;
        double worstRadiance = 0.0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const glm::vec4 w = want.values.rgba(x, y), g = got.values.rgba(x, y);
                distanceSame += w.a == g.a;
                if (want.gathers.rgba(x, y) == got.gathers.rgba(x, y)) {
                    ++gatherSame;
                } else {
                    // A gather picks the 2 x 2 texels by floor(p - 0.5): right on a texel
                    // centre (p - 0.5 whole, as some border queries are) the two paths'
                    // coordinates, a few ulps apart, may pick the neighbouring 2 x 2. Any
                    // other difference is a wrong tile or gutter.
                    const glm::vec4 qk = q[std::size_t(kH - 1 - y) * kW + std::size_t(x)];
                    const glm::vec3 f = glsl::cubeFaceUv(glm::vec3(qk));
                    const glm::vec2 p = glm::vec2(f) * float(c.n) - 0.5f;
                    const glm::vec2 off = glm::abs(p - glm::round(p));
                    gatherUnexplained += std::min(off.x, off.y) > 1e-3f;
                }
                // The bilinear weights come from the texel coordinate's fraction, which the
                // atlas path reaches through other arithmetic (an offset and a division by
                // the atlas size): both filters quantise the fraction (GL leaves the
                // precision to the implementation, commonly 8 bits), so the two may weigh
                // the 2 x 2 texels one step of 1/256 apart. Bound: that step times the
                // footprint's spread (the gather of each channel would give it; the largest
                // radiance here is 4).
                const double err = glm::length(glm::vec3(w) - glm::vec3(g));
                worstRadiance = std::max(worstRadiance, err);
                radianceWithin += err <= std::sqrt(3.0) * 4.0 / 256.0;
            }
        const long total = long(kW) * kH;
        std::printf("n %d %s: %d of %d tiles stored, atlas %dx%dx%d; distance equal %ld/%ld, "
                    "gather equal %ld/%ld, radiance worst %.3g\n",
                    c.n, c.half ? "half" : "float", t.slots - 1,
                    kLayers * 6 * t.tilesPerFace * t.tilesPerFace, t.width(), t.height(), t.pages,
                    distanceSame, total, gatherSame, total, worstRadiance);
        EXPECT_EQ(distanceSame, total) << "texelFetch through the table is exact";
        EXPECT_EQ(radianceWithin, total);
        EXPECT_EQ(gatherUnexplained, 0) << "gathers differing off a texel centre";
    }
}

namespace {

// Bytes of level 0 of a texture, from its real size and format as GL reports them.
std::size_t textureBytes(GLuint id) {
    if (id == 0) return 0;
    GLint w = 0, h = 0, d = 0, format = 0;
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_HEIGHT, &h);
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_DEPTH, &d);
    glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    const std::size_t texel = format == GL_RGBA32F   ? 16
                              : format == GL_RGBA16F ? 8
                              : format == GL_RGBA16I ? 8
                                                     : 0;
    EXPECT_NE(texel, 0u) << "unexpected format " << format;
    return std::size_t(w) * std::size_t(h) * std::size_t(std::max(d, 1)) * texel;
}

class LayerTilesStore : public test::RoomProbe {};

} // namespace

// Layered mode on the cooked room: the store counts exactly the textures it holds (the
// composite's cube, the tiles' atlas and table, the sky), and the layered probe costs less
// than the composite plus one full cube per object layer.
TEST_F(LayerTilesStore, ByteCountIsTheTexturesReallyHeld) {
    ReflectionProbeSystem& system = renderer_->probes();
    const DistanceStore& store = *system.store<DistanceStore>();
    std::size_t compositeOnly = 0;
    for (const DistanceMethod m : {DistanceMethod::Bisection, DistanceMethod::Layered}) {
        useProbe(probeFor(m));
        renderer_->render(scene_->camera(kWidth, kHeight));
        const ecs::Entity probe = scene_->probeEntity();
        const DistanceProbeGpu* g = store.probe(probe);
        ASSERT_TRUE(g);
        const std::size_t real = textureBytes(g->layers.id()) + textureBytes(g->sky.id()) +
                                 textureBytes(g->tiles.atlas.id()) +
                                 textureBytes(g->tiles.table.id());
        EXPECT_EQ(store.gpuBytes(), real) << toString(m);
        if (m == DistanceMethod::Bisection) {
            compositeOnly = real;
            continue;
        }
        const DistanceProbeAsset& a = *store.asset(probe);
        ASSERT_GT(a.objectLayerCount(), 0);
        const std::size_t full = std::size_t(a.objectLayerCount()) * cubeArrayBytes(a.faceRes, 1);
        const auto start = std::chrono::steady_clock::now();
        const LayerTiles t = tileObjectLayers(a); // the slots, for the report
        const double tileMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        const auto uploadStart = std::chrono::steady_clock::now();
        const LayerTileTextures uploaded = uploadLayerTiles(t);
        glFinish();
        const double uploadMs = std::chrono::duration<double, std::milli>(
                                    std::chrono::steady_clock::now() - uploadStart)
                                    .count();
        const auto wholeStart = std::chrono::steady_clock::now();
        const gpu::Texture whole = createCubeArray(a.faceRes, a.objectLayerCount());
        for (int L = 1; L <= a.objectLayerCount(); ++L)
            uploadCube(whole, L - 1, a.layers[std::size_t(L)]);
        glFinish();
        const double wholeMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wholeStart)
                .count();
        std::printf("object layers: tiling on the CPU %.1f ms + uploading the tiles %.1f ms; "
                    "uploading them whole %.1f ms\n",
                    tileMs, uploadMs, wholeMs);
        std::printf("room %d^2: composite only %.2f MiB, layered %.2f MiB (tiles %.2f MiB, "
                    "%d of %d tiles; full object layers would be %.2f MiB)\n",
                    a.faceRes, double(compositeOnly) / 1048576.0, double(real) / 1048576.0,
                    double(g->tileBytes) / 1048576.0, t.slots - 1,
                    a.objectLayerCount() * 6 * t.tilesPerFace * t.tilesPerFace,
                    double(full) / 1048576.0);
        // The tile side's trade (finer tiles hug the outlines, the gutter costs more), for
        // the report: per side, tiles stored and the atlas and table bytes as half floats.
        for (const int side : {8, 16, 32, 64}) {
            const LayerTiles s = tileObjectLayers(a, side, true);
            std::printf("  tile %2d: %5d of %5d tiles, %.2f MiB\n", side, s.slots - 1,
                        a.objectLayerCount() * 6 * s.tilesPerFace * s.tilesPerFace,
                        double(layerTileBytes(s)) / 1048576.0);
        }
        const std::vector<int> perLayer = t.storedPerLayer();
        for (std::size_t L = 0; L < perLayer.size(); ++L)
            std::printf("  layer %2zu %-24s %4d of %d tiles\n", L + 1, a.layers[L + 1].name.c_str(),
                        perLayer[L], 6 * t.tilesPerFace * t.tilesPerFace);
        EXPECT_EQ(real - compositeOnly, g->tileBytes);
        EXPECT_LT(g->tileBytes, full);
    }
}
