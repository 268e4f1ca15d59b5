// Near objects packed into a bounded number of layers (plan_layer_packing.h, issue 34): by
// hand-made coverages whose right packing is known, and on a cluttered scene of 2,000 nodes,
// whose plan used to propose 2,000 object layers that the runtime refuses (at most 63).
#include "assetcooker/lib/plan/effect_plan.h"
#include "assetcooker/lib/plan/plan_layer_packing.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "plan/code_scene.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

using namespace specula;

namespace {

using Coverage = std::vector<std::vector<std::uint32_t>>;

} // namespace

TEST(LayerPacking, ObjectsThatNeverOverlapShareOneLayer) {
    const Coverage c{{0, 1}, {2, 3}, {4}, {5, 6, 7}};
    const LayerPacking p = packNearObjects(c, 8, 63);
    ASSERT_EQ(p.layers.size(), 1u);
    EXPECT_EQ(p.layers[0], (std::vector<std::size_t>{0, 1, 2, 3}));
    EXPECT_EQ(p.forced, 0u);
}

TEST(LayerPacking, EachObjectJoinsTheFirstLayerItOverlapsNowhere) {
    // 0 and 1 overlap at texel 1; 2 overlaps 0 only (texel 0), so it joins 1's layer; 3
    // overlaps everything placed so far in both layers' texels: a third layer.
    const Coverage c{{0, 1}, {1, 2}, {0}, {0, 1, 2}};
    const LayerPacking p = packNearObjects(c, 3, 63);
    ASSERT_EQ(p.layers.size(), 3u);
    EXPECT_EQ(p.layers[0], (std::vector<std::size_t>{0}));
    EXPECT_EQ(p.layers[1], (std::vector<std::size_t>{1, 2}));
    EXPECT_EQ(p.layers[2], (std::vector<std::size_t>{3}));
    EXPECT_EQ(p.forced, 0u);
}

TEST(LayerPacking, PastTheCapAnObjectJoinsTheLayerItOverlapsLeast) {
    // Two layers at most. 0 covers 0..3, 1 covers 3..5 (a second layer); 2 covers 0..1 and 5:
    // it overlaps layer 0 in two texels and layer 1 in one, so it joins layer 1.
    const Coverage c{{0, 1, 2, 3}, {3, 4, 5}, {0, 1, 5}};
    const LayerPacking p = packNearObjects(c, 6, 2);
    ASSERT_EQ(p.layers.size(), 2u);
    EXPECT_EQ(p.layers[1], (std::vector<std::size_t>{1, 2}));
    EXPECT_EQ(p.forced, 1u);
    EXPECT_EQ(p.forcedTexels, 1u);
}

TEST(LayerPacking, AClutteredSceneIsPlannedWithinTheRuntimesLayerCap) {
    test::CodeScene s;
    s.node("mirror", glm::vec3(0.f), test::sphereMesh(0.5f), "{\"specula_reflector\": true}");
    s.node("probe", glm::vec3(0.f), nullptr, "{\"specula_probe\": {\"cell_size\": 1.5}}");
    const auto box = test::boxMesh(glm::vec3(0.5f));
    std::mt19937 rng(34);
    std::uniform_real_distribution<float> coord(-6.f, 6.f), size(0.05f, 0.3f);
    constexpr int kNodes = 2000;
    for (int i = 0; i < kNodes; ++i) {
        glm::vec3 p;
        do
            p = glm::vec3(coord(rng), coord(rng), coord(rng));
        while (glm::dot(p, p) < 2.f);
        s.node("box" + std::to_string(i), p, box, "", size(rng));
    }
    updateWorldTransforms(s.reg);
    const SceneMarkup m = readSceneMarkup(s.reg, s.scene, "clutter.gltf");
    const glm::vec3 c = markupProbeCentre(s.reg, m, s.scene);
    const EffectPlan plan =
        planEffects(s.reg, m, c, markupReflectorReach(s.reg, m, c, markupCellSize(m)));
    ASSERT_EQ(plan.mode, "layered");
    std::size_t objectLayers = 0, placed = 0;
    std::set<std::string> names;
    for (const PlannedLayer& l : plan.layers) {
        if (l.name == "distant") continue;
        ++objectLayers;
        placed += l.objects.size();
        names.insert(l.objects.begin(), l.objects.end());
        // A shared layer holds objects at several distances: only per-pixel rectification
        // serves them all.
        if (l.objects.size() > 1) {
            EXPECT_EQ(l.method, "bisection") << l.name;
        }
    }
    std::printf("[layer packing] %zu near objects in %zu object layers: %s\n", placed, objectLayers,
                plan.layerPacking.c_str());
    EXPECT_LE(objectLayers, std::size_t(glsl::kMaxDistanceLayers - 1));
    EXPECT_GT(placed, std::size_t(glsl::kMaxDistanceLayers)); // the cap was needed
    EXPECT_EQ(names.size(), placed);                          // every near object once
    EXPECT_NE(plan.modeReason.find("packed into"), std::string::npos) << plan.modeReason;
}
