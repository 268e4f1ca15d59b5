// Per-texel roughness (issue 14): a reflector whose material has a metallic-roughness texture
// reads factor x the texture's G channel at each point's TEXCOORD_0 (reflector_roughness.h).
// The loader and the markup keep the texture (the markup's "material" is tested in
// tests/plan/material_reflector_test.cpp), roughnessAt is checked in closed form, the
// effect plan takes the sharpest texel; the truth reads the map per hit, and the footprint
// twin reading it per pixel beats the twin given the map's mean (roughness_map_truth_test.cpp).
#include "assetcooker/lib/plan/plan_glossy.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/system/reflection_probe.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "engine/scene/components.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <map>

using namespace specula;

namespace {

const std::string kBands = SPECULA_SOURCE_DIR "/assets/room/room_rough_bands.gltf";
const std::string kBandsPng = SPECULA_SOURCE_DIR "/assets/room/roughness_bands.png";
const std::string kRoom = SPECULA_SOURCE_DIR "/assets/room/room.gltf";

// The PNG's G channel read by OpenImageIO on its own (8-bit codes), row by row.
std::vector<int> pngGreen(int& width, int& height) {
    auto in = OIIO::ImageInput::open(kBandsPng);
    EXPECT_TRUE(in) << kBandsPng;
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    std::vector<std::uint8_t> px(std::size_t(width) * height * spec.nchannels);
    EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, px.data()));
    std::vector<int> green;
    for (std::size_t i = 1; i < px.size(); i += std::size_t(spec.nchannels))
        green.push_back(px[i]);
    return green;
}

const ReflectorMarkup* reflector(const SceneMarkup& m, const std::string& node) {
    for (const ReflectorMarkup& r : m.reflectors)
        if (r.node == node) return &r;
    return nullptr;
}

const MaterialData* materialNamed(ecs::Registry& reg, const std::string& name) {
    const MaterialData* found = nullptr;
    reg.view<Mesh>().each([&](ecs::Entity, Mesh& mesh) {
        for (const Primitive& p : mesh.primitives)
            if (p.material && p.material->name == name) found = p.material.get();
    });
    return found;
}

} // namespace

// 1. The loader keeps the texture with its summaries; the markup's "material" hands the sphere
// and torus factor 1 and that texture, and the probe's Reflector components carry it; the plain
// room's reflectors stay uniform.
TEST(RoughnessMap, LoaderAndMarkupKeepTheTexture) {
    int w = 0, h = 0;
    const std::vector<int> g = pngGreen(w, h);
    ASSERT_EQ(w, 32);
    ASSERT_EQ(h, 32);
    // The PNG: bands across u, 4 texels wide, G 20 then 102, the same on every row.
    double sum = 0.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            ASSERT_EQ(g[std::size_t(y * w + x)], (x / 4) % 2 == 0 ? 20 : 102) << x << ", " << y;
            sum += g[std::size_t(y * w + x)];
        }
    const float mean = float(sum / (255.0 * w * h)); // (20 + 102) / 2 / 255 = 61 / 255
    EXPECT_NEAR(mean, 61.f / 255.f, 1e-7f);

    ProbeScene scene(kBands, "");
    const MaterialData* md = materialNamed(scene.registry, "banded_metal");
    ASSERT_TRUE(md);
    ASSERT_TRUE(md->metallicRoughnessTexture);
    const Image& map = *md->metallicRoughnessTexture;
    EXPECT_EQ(map.width, 32);
    EXPECT_EQ(map.height, 32);
    EXPECT_FLOAT_EQ(md->roughnessFactor, 1.f);
    EXPECT_NEAR(md->roughnessTextureMin, 20.f / 255.f, 1e-6f);
    EXPECT_NEAR(md->roughnessTextureMean, mean, 1e-6f);
    EXPECT_NEAR(md->roughness(), mean, 1e-6f);
    EXPECT_NEAR(roughnessMapMin(&map), 20.f / 255.f, 1e-6f);
    EXPECT_NEAR(roughnessMapMean(&map), mean, 1e-6f);
    EXPECT_EQ(roughnessMapMin(nullptr), 1.f);
    EXPECT_EQ(roughnessMapMean(nullptr), 1.f);
    // Linear, not sRGB-decoded: texel (5, 0) holds 102 / 255 in G.
    EXPECT_NEAR(map.at(5, 0)[1], 102.f / 255.f, 1e-6f);

    for (const char* node : {"sphere", "torus"}) {
        const ReflectorMarkup* r = reflector(scene.markup, node);
        ASSERT_TRUE(r) << node;
        EXPECT_FLOAT_EQ(r->roughness, 1.f) << node;
        EXPECT_EQ(r->roughnessMap.get(), &map) << node;
    }
    attachProbeComponents(scene.registry, scene.markup, ReflectionProbe{"unused"});
    int carried = 0;
    scene.registry.view<Reflector>().each([&](ecs::Entity, const Reflector& r) {
        EXPECT_EQ(r.roughnessMap.get(), &map);
        EXPECT_FLOAT_EQ(r.roughness, 1.f);
        ++carried;
    });
    EXPECT_EQ(carried, 2);

    ProbeScene room(kRoom, "");
    ASSERT_EQ(room.markup.reflectors.size(), 2u);
    for (const ReflectorMarkup& r : room.markup.reflectors) {
        EXPECT_FALSE(r.roughnessMap) << r.node;
        EXPECT_EQ(r.roughness, 0.f) << r.node; // mirrors, as before
    }
}

// 2. roughnessAt in closed form on the loaded map: GL_LINEAR, no mipmaps, GL_REPEAT.
TEST(RoughnessMap, RoughnessAtIsTheBilinearRepeatedGreenTimesTheFactor) {
    ProbeScene scene(kBands, "");
    const Image* map = reflector(scene.markup, "sphere")->roughnessMap.get();
    ASSERT_TRUE(map);
    const float lo = 20.f / 255.f, hi = 102.f / 255.f;
    for (int x = 0; x < 32; ++x)
        for (const int y : {0, 13, 31}) {
            const glm::vec2 uv((float(x) + 0.5f) / 32.f, (float(y) + 0.5f) / 32.f);
            const float g = (x / 4) % 2 == 0 ? lo : hi;
            ASSERT_NEAR(roughnessAt(1.f, map, uv), g, 1e-6f) << x;
            ASSERT_NEAR(roughnessAt(0.5f, map, uv), 0.5f * g, 1e-6f) << x;
            // Repeat on both axes: a whole period away reads the same.
            ASSERT_NEAR(roughnessAt(0.7f, map, uv + glm::vec2(1.f, 0.f)), 0.7f * g, 1e-6f) << x;
            ASSERT_NEAR(roughnessAt(0.7f, map, uv + glm::vec2(0.f, -1.f)), 0.7f * g, 1e-6f) << x;
            ASSERT_EQ(roughnessAt(0.f, map, uv), 0.f);
            // Clamped to 1: 20 x 102 / 255 = 8.
            if (g == hi) {
                ASSERT_EQ(roughnessAt(20.f, map, uv), 1.f);
            }
        }
    // Half-way between a 20 texel (3) and a 102 texel (4): u = 4 / 32; and across the wrap,
    // between texel 31 (102) and texel 0 (20): u = 0 and u = 1.
    for (const float u : {4.f / 32.f, 8.f / 32.f, 0.f, 1.f, -1.f})
        EXPECT_NEAR(roughnessAt(1.f, map, {u, 0.3f}), 0.5f * (lo + hi), 1e-6f) << u;
    // A quarter of the way from texel 3's centre to texel 4's.
    EXPECT_NEAR(roughnessAt(1.f, map, {3.75f / 32.f, 0.6f}), 0.75f * lo + 0.25f * hi, 1e-6f);
    // Any uv: a whole period on either axis reads the same.
    for (const glm::vec2 uv : {glm::vec2(0.3f, 0.7f), glm::vec2(0.123f, 0.456f)}) {
        EXPECT_NEAR(roughnessAt(1.f, map, uv + glm::vec2(1.f, 0.f)), roughnessAt(1.f, map, uv),
                    1e-5f);
        EXPECT_NEAR(roughnessAt(1.f, map, uv + glm::vec2(0.f, -1.f)), roughnessAt(1.f, map, uv),
                    1e-5f);
    }
    // Without a map: the factor.
    EXPECT_EQ(roughnessAt(0.35f, nullptr, {0.2f, 0.2f}), 0.35f);
}

// 6. The effect plan serves the sharpest lobe the reflector shows: factor 1 x its smoothest
// texel, 20 / 255, not the mean 61 / 255 nor the factor.
TEST(RoughnessMap, ThePlanTakesTheSharpestTexel) {
    ProbeScene scene(kBands, "");
    std::vector<PlannedReflector> planned;
    const SharpestLobe sharpest = planReflectors(scene.markup, planned);
    std::map<std::string, float> byName;
    for (const PlannedReflector& p : planned)
        byName[p.name] = p.roughness;
    ASSERT_EQ(byName.size(), 2u);
    EXPECT_NEAR(byName.at("sphere"), 20.f / 255.f, 1e-6f);
    EXPECT_NEAR(byName.at("torus"), 20.f / 255.f, 1e-6f);
    EXPECT_NEAR(sharpest.roughness, 20.f / 255.f, 1e-6f);
    EXPECT_NEAR(sharpest.deg, ggxLobeHalfWidthDeg(20.f / 255.f), 1e-4f);
}
