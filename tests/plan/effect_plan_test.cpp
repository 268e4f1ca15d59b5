// The effect plan on small canonical scenes whose right answer is known.
#include "assetcooker/lib/plan/effect_plan.h"
#include "plan/code_scene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace specula;

namespace {

// A code scene with the planner's entry points: reflectorAndProbe() adds the usual pair.
struct SceneBuilder : test::CodeScene {
    static std::shared_ptr<MeshData> box(glm::vec3 half) { return test::boxMesh(half); }
    static std::shared_ptr<MeshData> sphere(float r) { return test::sphereMesh(r); }
    // A mirror sphere at the probe, radius 0.5, and the probe node (cell 1.5 m).
    void
    reflectorAndProbe(const std::string& probeExtras = "{\"specula_probe\": {\"cell_size\": 1.5}}",
                      const std::string& reflectorExtras = "{\"specula_reflector\": true}") {
        node("mirror", glm::vec3(0.f), sphere(0.5f), reflectorExtras);
        node("probe", glm::vec3(0.f), nullptr, probeExtras);
    }
    EffectPlan plan() {
        updateWorldTransforms(reg);
        const SceneMarkup m = readSceneMarkup(reg, scene, "test.gltf");
        const glm::vec3 c = markupProbeCentre(reg, m, scene);
        return planEffects(reg, m, c, markupReflectorReach(reg, m, c, markupCellSize(m)));
    }
};

const PlannedObject& object(const EffectPlan& p, const std::string& name) {
    for (const PlannedObject& o : p.objects)
        if (o.name == name) return o;
    throw std::runtime_error("no object " + name);
}

} // namespace

TEST(EffectPlan, EmptyRoomUnderASkyIsAClassicEnvironmentMap) {
    SceneBuilder s;
    s.reflectorAndProbe();
    const EffectPlan p = s.plan();
    std::printf("%s", p.toText().c_str());
    EXPECT_EQ(p.mode, "envmap");
    EXPECT_EQ(p.features, "envmap");
    EXPECT_FALSE(p.fresnel);
}

TEST(EffectPlan, FarMountainIsDistant) {
    SceneBuilder s;
    s.reflectorAndProbe();
    s.node("mountain", glm::vec3(0, 0, -2000), SceneBuilder::box(glm::vec3(300, 200, 50)));
    const EffectPlan p = s.plan();
    EXPECT_EQ(object(p, "mountain").decision, "distant");
    // asin(1.3 m / 1950 m) = 0.04 deg < 1 deg.
    EXPECT_LT(object(p, "mountain").parallaxDeg, 0.1f);
    EXPECT_EQ(p.mode, "envmap");
}

TEST(EffectPlan, LargeWallCloseByIsRectifiedPerPixel) {
    SceneBuilder s;
    s.reflectorAndProbe();
    s.node("wall", glm::vec3(0, 0, -2.5f), SceneBuilder::box(glm::vec3(6, 6, 0.05f)));
    const EffectPlan p = s.plan();
    EXPECT_EQ(object(p, "wall").decision, "rectify");
    EXPECT_EQ(p.mode, "single");
    ASSERT_EQ(p.layers.size(), 1u);
    EXPECT_EQ(p.layers[0].method, "bisection");
    EXPECT_EQ(p.features, "bisection");
}

TEST(EffectPlan, SmallFarSphereGetsTheAverageDistance) {
    SceneBuilder s;
    s.reflectorAndProbe();
    s.node("ball", glm::vec3(0, 0, -8), SceneBuilder::sphere(0.3f));
    const EffectPlan p = s.plan();
    const PlannedObject& ball = object(p, "ball");
    // Solid angle of a sphere of radius 0.3 at 8 m: 2 pi (1 - cos asin(0.3/8)) = 0.0044 sr.
    // It falls between the analysis rays, so the plan judges it by the bounding sphere of
    // its box (radius x sqrt 3): at most 3x the true figure, never less.
    const double exact = 2 * 3.14159 * (1 - std::cos(std::asin(0.3 / 8)));
    EXPECT_GE(ball.solidAngle, exact * 0.95);
    EXPECT_LE(ball.solidAngle, exact * 3.1);
    EXPECT_EQ(ball.decision, "avgdist");
    EXPECT_EQ(p.mode, "single");
    EXPECT_EQ(p.features, "avgdist");
}

TEST(EffectPlan, SolidAngleThresholdSeparatesTheMethods) {
    // Spheres at 3 m whose solid angle sits just below and just above 0.379 sr (a 20 degree
    // cone): half-angles 19 and 21 degrees.
    for (float halfDeg : {19.f, 21.f}) {
        SceneBuilder s;
        s.reflectorAndProbe();
        const float r = 3.f * std::sin(halfDeg * 3.14159265f / 180.f);
        s.node("ball", glm::vec3(0, 0, -3), SceneBuilder::sphere(r));
        const EffectPlan plan = s.plan();
        const PlannedObject& ball = object(plan, "ball");
        std::printf("half-angle %.0f deg: %.3f sr -> %s\n", halfDeg, ball.solidAngle,
                    ball.decision.c_str());
        EXPECT_EQ(ball.decision, halfDeg < 20.f ? "avgdist" : "rectify");
    }
}

TEST(EffectPlan, ObjectBehindAnotherGetsLayers) {
    SceneBuilder s;
    s.reflectorAndProbe();
    s.node("pillar", glm::vec3(0, 0, -2.5f), SceneBuilder::box(glm::vec3(0.2f, 1.5f, 0.2f)));
    s.node("wall", glm::vec3(0, 0, -5), SceneBuilder::box(glm::vec3(5, 3, 0.05f)));
    const EffectPlan p = s.plan();
    // Nearest pillar point at 2.3 m, reach 1.3 m: asin(1.3 / 2.3) = 34 degrees of parallax.
    EXPECT_EQ(p.mode, "layered");
    ASSERT_EQ(p.layers.size(), 2u);
    EXPECT_EQ(p.layers[0].objects, std::vector<std::string>{"pillar"});
    EXPECT_EQ(p.layers[1].objects, std::vector<std::string>{"wall"});
    EXPECT_EQ(p.flavour, "distance");
}

TEST(EffectPlan, NearOccluderWithLargeParallaxAsksForTheLightField) {
    // A thin post 1.6 m away (nearest point 1.5 m) before a wall at 4.95 m: moving the
    // reflector by the reach (1.3 m) uncovers 1.3 (1/1.5 - 1/4.95) = 0.6 rad = 34 degrees of
    // wall never seen from the probe centre.
    SceneBuilder s;
    s.reflectorAndProbe();
    s.node("post", glm::vec3(0, 0, -1.6f), SceneBuilder::box(glm::vec3(0.1f, 0.5f, 0.1f)));
    s.node("wall", glm::vec3(0, 0, -5), SceneBuilder::box(glm::vec3(5, 3, 0.05f)));
    const EffectPlan p = s.plan();
    EXPECT_EQ(p.flavour, "lightfield") << p.flavourReason;
}

TEST(EffectPlan, ObjectsApartAreMergedIntoOneLayer) {
    SceneBuilder s;
    s.reflectorAndProbe();
    s.node("east", glm::vec3(6, 0, 0), SceneBuilder::box(glm::vec3(0.05f, 1, 1)));
    s.node("west", glm::vec3(-6, 0, 0), SceneBuilder::box(glm::vec3(0.05f, 1, 1)));
    const EffectPlan p = s.plan();
    EXPECT_EQ(p.mode, "single");
    ASSERT_EQ(p.layers.size(), 1u);
    EXPECT_EQ(p.layers[0].objects.size(), 2u);
}

TEST(EffectPlan, UserNeedsAreHonouredAndReported) {
    SceneBuilder s;
    s.reflectorAndProbe("{\"specula_probe\": {\"max_error_deg\": 30, \"fresnel\": true, "
                        "\"flavour\": \"lightfield\"}}");
    s.node("ball", glm::vec3(0, 0, -8), SceneBuilder::sphere(0.3f));
    const EffectPlan p = s.plan();
    // 30 degrees tolerance makes the ball (9.7 degrees of parallax) distant.
    EXPECT_EQ(object(p, "ball").decision, "distant");
    EXPECT_TRUE(p.fresnel);
    EXPECT_EQ(p.flavour, "lightfield");
    EXPECT_EQ(p.userNeeds.size(), 3u);
    EXPECT_NE(p.toText().find("user need"), std::string::npos);
}

TEST(EffectPlan, EachProbeOfALevelIsPlannedWithItsOwnNeeds) {
    SceneBuilder s;
    s.reflectorAndProbe("{\"specula_probe\": {\"flavour\": \"lightfield\"}}");
    s.node("probe_2", glm::vec3(4, 0, 0), nullptr, "{\"specula_probe\": {\"fresnel\": true}}");
    s.node("ball", glm::vec3(0, 0, -8), SceneBuilder::sphere(0.3f));
    updateWorldTransforms(s.reg);
    const SceneMarkup m = readSceneMarkup(s.reg, s.scene, "test.gltf");
    ASSERT_EQ(m.probes.size(), 2u);
    const auto planOf = [&](int probe) {
        const glm::vec3 c = probe >= 0 ? m.probes[std::size_t(probe)].position : glm::vec3(0.f);
        return planEffects(s.reg, m, c, markupReflectorReach(s.reg, m, c, 1.5f), {}, probe);
    };
    const EffectPlan first = planOf(0), second = planOf(1), none = planOf(-1);
    EXPECT_EQ(first.flavour, "lightfield");
    ASSERT_EQ(first.userNeeds.size(), 1u);
    EXPECT_EQ(first.userNeeds[0], "flavour = lightfield");
    ASSERT_EQ(second.userNeeds.size(), 1u);
    EXPECT_EQ(second.userNeeds[0], "fresnel = true");
    EXPECT_TRUE(second.fresnel);
    EXPECT_TRUE(none.userNeeds.empty());
}

TEST(EffectPlan, FresnelOnlyWhereAMaterialAsks) {
    SceneBuilder a;
    a.reflectorAndProbe("{\"specula_probe\": {}}", "{\"specula_reflector\": {\"f0\": 0.04}}");
    EXPECT_TRUE(a.plan().fresnel);
    SceneBuilder b;
    b.reflectorAndProbe("{\"specula_probe\": {}}", "{\"specula_reflector\": {\"f0\": 1.0}}");
    EXPECT_FALSE(b.plan().fresnel);
}

TEST(EffectPlan, DefaultRoomIsMixed) {
    ecs::Registry reg;
    const std::string path = std::string(SPECULA_SOURCE_DIR) + "/assets/room/room.gltf";
    const LoadedScene scene = loadGltf(path, reg);
    const SceneMarkup m = readSceneMarkup(reg, scene, path);
    const glm::vec3 c = markupProbeCentre(reg, m, scene);
    const EffectPlan p = planEffects(reg, m, c, markupReflectorReach(reg, m, c, markupCellSize(m)));
    std::printf("%s", p.toText().c_str());
    EXPECT_EQ(p.mode, "layered");
    EXPECT_EQ(object(p, "floor").decision, "rectify");
    EXPECT_EQ(object(p, "wall_north").decision, "rectify");
    EXPECT_EQ(object(p, "column_red").decision, "avgdist");
    EXPECT_NE(p.features.find("bisection"), std::string::npos);
    EXPECT_NE(p.features.find("avgdist"), std::string::npos);
    EXPECT_EQ(p.flavour, "distance");
    // Layer order respects occlusion: each column precedes the wall behind it.
    auto layerOf = [&](const std::string& name) {
        for (std::size_t i = 0; i < p.layers.size(); ++i)
            for (const std::string& o : p.layers[i].objects)
                if (o == name) return int(i);
        return -1;
    };
    EXPECT_LT(layerOf("column_red"), layerOf("wall_east") >= 0 ? 99 : -1);
    for (const char* col : {"column_red", "column_green", "column_blue", "column_yellow"})
        EXPECT_GE(layerOf(col), 0) << col;
}
