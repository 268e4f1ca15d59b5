// The effect plan weighs rough reflectors (issue 14, plan_glossy.h): where the sharpest
// reflector's GGX lobe, half-width theta = 2 atan(r^2), is wider than the parallax a lookup
// would correct, the cheaper lookup is chosen and the plan says why. Every expectation below
// is derived from the scene's geometry and theta computed here, not read back from the plan:
// an object's parallax is asin(reach / nearest), a small occluder uncovers reach (1 / d_front
// - 1 / d_back) of what lies behind it; reach = the cell's corner, 0.75 sqrt 3 = 1.30 m.
#include "assetcooker/lib/plan/effect_plan.h"
#include "plan/code_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace specula;

namespace {

constexpr double kPi = 3.14159265358979;
const double kReach = 0.75 * std::sqrt(3.0); // the 1.5 m cell's corner; the mirror is inside

double lobeDeg(double r) {
    return 2.0 * std::atan(r * r) * 180.0 / kPi;
}
double parallaxDeg(double nearest) {
    return std::asin(std::min(1.0, kReach / nearest)) * 180.0 / kPi;
}
double uncoveredDeg(double front, double back) {
    return kReach * (1.0 / front - 1.0 / back) * 180.0 / kPi;
}

std::string reflectorExtras(float roughness) {
    return "{\"specula_reflector\": {\"roughness\": " + std::to_string(roughness) + "}}";
}

struct Scene : test::CodeScene {
    // A sphere reflector of radius 0.5 at the probe (the origin) with `roughness`, and the
    // probe node (cell 1.5 m).
    explicit Scene(float roughness) {
        node("mirror", glm::vec3(0.f), test::sphereMesh(0.5f), reflectorExtras(roughness));
        node("probe", glm::vec3(0.f), nullptr, "{\"specula_probe\": {\"cell_size\": 1.5}}");
    }
    // A hall open to the sky: a floor whose top is 2.95 m below the probe and four walls whose
    // inner faces are 4.45 m away.
    void hall() {
        node("floor", glm::vec3(0, -3, 0), test::boxMesh(glm::vec3(5, 0.05f, 5)));
        node("wall_n", glm::vec3(0, 0, -4.5f), test::boxMesh(glm::vec3(4.5f, 3, 0.05f)));
        node("wall_s", glm::vec3(0, 0, 4.5f), test::boxMesh(glm::vec3(4.5f, 3, 0.05f)));
        node("wall_e", glm::vec3(4.5f, 0, 0), test::boxMesh(glm::vec3(0.05f, 3, 4.5f)));
        node("wall_w", glm::vec3(-4.5f, 0, 0), test::boxMesh(glm::vec3(0.05f, 3, 4.5f)));
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

// The plan without what only a rough reflector adds (its lobe and the reflector list).
nlohmann::json withoutLobe(const EffectPlan& p) {
    nlohmann::json j = p.toJson();
    j.erase("lobe");
    j.erase("reflectors");
    return j;
}

} // namespace

TEST(GlossyPlan, TheLobeIsTheGgxHalfWidthOfTheSharpestReflector) {
    for (float r : {0.f, 0.1f, 0.35f, 0.5f, 1.f})
        EXPECT_NEAR(ggxLobeHalfWidthDeg(r), lobeDeg(r), 1e-3) << r;
    EXPECT_EQ(ggxLobeHalfWidthDeg(std::nanf("")), 0.f);
    // Two reflectors: the plan reports both and weighs the sharper.
    Scene s(0.6f);
    s.node("second", glm::vec3(0.5f, 0, 0), test::sphereMesh(0.1f), reflectorExtras(0.3f));
    const EffectPlan p = s.plan();
    ASSERT_EQ(p.reflectors.size(), 2u);
    EXPECT_NEAR(p.reflectors[0].lobeDeg, lobeDeg(0.6), 1e-3);
    EXPECT_NEAR(p.lobeDeg, lobeDeg(0.3), 1e-3);
    EXPECT_NE(p.lobeReason.find("second"), std::string::npos) << p.lobeReason;
}

TEST(GlossyPlan, RoughReflectorInAHallGetsTheDirectionOnlyLookupWithTheReason) {
    Scene mirror(0.f);
    mirror.hall();
    const EffectPlan m = mirror.plan();
    // A mirror rectifies the hall: the floor's parallax is asin(1.3 / 2.95) = 26.1 deg, the
    // walls' asin(1.3 / 4.45) = 17.0 deg, both far above the 1 deg tolerance.
    EXPECT_EQ(object(m, "floor").decision, "rectify");
    EXPECT_EQ(object(m, "wall_n").decision, "rectify");
    EXPECT_NE(m.features.find("bisection"), std::string::npos) << m.features;

    // r = 0.5: theta = 2 atan(0.25) = 28.1 deg hides both: the direction-only lookup.
    Scene rough(0.5f);
    rough.hall();
    const EffectPlan p = rough.plan();
    std::printf("%s", p.toText().c_str());
    EXPECT_EQ(p.mode, "envmap");
    EXPECT_EQ(p.features, "envmap");
    for (const char* o : {"floor", "wall_n", "wall_s", "wall_e", "wall_w"}) {
        EXPECT_EQ(object(p, o).decision, "distant") << o;
        EXPECT_NE(object(p, o).reason.find("blur hides it"), std::string::npos)
            << object(p, o).reason;
    }
    EXPECT_NE(p.modeReason.find("lobe"), std::string::npos) << p.modeReason;
    EXPECT_NE(p.toText().find("lobe     28.1 deg"), std::string::npos) << p.toText();
}

TEST(GlossyPlan, EachObjectIsCorrectedExactlyWhileItsParallaxExceedsTheLobe) {
    // Across roughness the hall's objects flip one by one, each where theta passes its own
    // parallax: walls (17.0 deg) from r = 0.4 (18.2 deg), the floor (26.1 deg) from r = 0.5.
    const std::pair<const char*, double> objects[] = {{"floor", 2.95}, {"wall_n", 4.45}};
    for (float r : {0.1f, 0.3f, 0.4f, 0.45f, 0.5f, 0.7f}) {
        Scene s(r);
        s.hall();
        const EffectPlan p = s.plan();
        for (const auto& [name, nearest] : objects) {
            const bool hidden = parallaxDeg(nearest) < lobeDeg(r);
            EXPECT_EQ(object(p, name).decision, hidden ? "distant" : "rectify")
                << name << " at r = " << r << ": parallax " << parallaxDeg(nearest) << " deg, lobe "
                << lobeDeg(r) << " deg";
        }
    }
}

TEST(GlossyPlan, SlightlyRoughReflectorBeforeANearWallIsPlannedAsAMirror) {
    // A wall 2.45 m away: 32 deg of parallax. At r = 0.1 the lobe (1.15 deg) is far narrower:
    // still per-pixel rectification, and the whole plan is the mirror's.
    const auto plan = [](float r) {
        Scene s(r);
        s.node("wall", glm::vec3(0, 0, -2.5f), test::boxMesh(glm::vec3(6, 6, 0.05f)));
        return s.plan();
    };
    const EffectPlan p = plan(0.1f), m = plan(0.f);
    EXPECT_EQ(object(p, "wall").decision, "rectify");
    EXPECT_EQ(p.mode, "single");
    ASSERT_EQ(p.layers.size(), 1u);
    EXPECT_EQ(p.layers[0].method, "bisection");
    EXPECT_EQ(withoutLobe(p), withoutLobe(m));
    EXPECT_NEAR(p.lobeDeg, lobeDeg(0.1), 1e-3);
    // Below the 1 deg tolerance (r = 0.05: 0.29 deg) the lobe is said to change nothing.
    EXPECT_NE(plan(0.05f).lobeReason.find("as a mirror"), std::string::npos);
}

TEST(GlossyPlan, ASharpReflectorBesideARoughOneKeepsTheMirrorPlan) {
    // One lookup serves the probe's reflectors: a mirror beside an r = 0.7 one decides.
    Scene both(0.7f), mirror(0.f);
    for (Scene* s : {&both, &mirror})
        s->hall();
    both.node("second", glm::vec3(0.5f, 0, 0), test::sphereMesh(0.1f), reflectorExtras(0.f));
    mirror.node("second", glm::vec3(0.5f, 0, 0), test::sphereMesh(0.1f), reflectorExtras(0.f));
    EXPECT_EQ(withoutLobe(both.plan()), withoutLobe(mirror.plan()));
}

TEST(GlossyPlan, OcclusionUnderTheBlurMergesTheLayers) {
    // A small pillar (nearest 2.2 m) before a wall (nearest 3.0 m): moving by the reach
    // uncovers 1.3 (1/2.2 - 1/3.0) = 9.0 deg of wall. Both stay near while theta is below
    // their parallax (36.2, 25.7 deg); the layers go once theta passes the 9.0 deg.
    const double uncovered = uncoveredDeg(2.2, 3.0);
    for (float r : {0.f, 0.25f, 0.35f, 0.45f}) {
        Scene s(r);
        s.node("pillar", glm::vec3(0, 0, -2.4f), test::boxMesh(glm::vec3(0.2f, 1.5f, 0.2f)));
        s.node("wall", glm::vec3(0, 0, -3.05f), test::boxMesh(glm::vec3(5, 3, 0.05f)));
        const EffectPlan p = s.plan();
        ASSERT_LT(lobeDeg(r), parallaxDeg(3.0)) << "the wall must stay near";
        EXPECT_EQ(object(p, "pillar").decision, "avgdist") << r;
        EXPECT_EQ(object(p, "wall").decision, "rectify") << r;
        const bool hidden = lobeDeg(r) > uncovered;
        EXPECT_EQ(p.mode, hidden ? "single" : "layered")
            << "r = " << r << ": lobe " << lobeDeg(r) << " deg, uncovered " << uncovered << " deg";
        if (hidden) {
            EXPECT_NE(p.modeReason.find("the blur hides the occlusion"), std::string::npos)
                << p.modeReason;
            ASSERT_EQ(p.layers.size(), 1u);
            EXPECT_EQ(p.layers[0].method, "bisection");
        }
    }
}

TEST(GlossyPlan, DisocclusionsUnderTheBlurNeedNoLightField) {
    // A post 0.9 m away before a wall 1.5 m away: 1.3 (1/0.9 - 1/1.5) = 33.1 deg uncovered,
    // over the 30 deg that asks for the light field. r = 0.7 (theta 52.2 deg) hides it while
    // the wall (60.1 deg of parallax) still needs rectifying.
    const auto plan = [](float r) {
        Scene s(r);
        s.node("post", glm::vec3(0, 0, -1.f), test::boxMesh(glm::vec3(0.1f, 0.5f, 0.1f)));
        s.node("wall", glm::vec3(0, 0, -1.55f), test::boxMesh(glm::vec3(5, 3, 0.05f)));
        return s.plan();
    };
    ASSERT_GT(uncoveredDeg(0.9, 1.5), 30.0);
    ASSERT_LT(uncoveredDeg(0.9, 1.5), lobeDeg(0.7));
    ASSERT_GT(parallaxDeg(1.5), lobeDeg(0.7));
    EXPECT_EQ(plan(0.f).flavour, "lightfield");
    const EffectPlan p = plan(0.7f);
    std::printf("%s", p.toText().c_str());
    EXPECT_EQ(p.flavour, "distance");
    EXPECT_NE(p.flavourReason.find("the blur hides the disocclusion"), std::string::npos)
        << p.flavourReason;
    EXPECT_EQ(object(p, "wall").decision, "rectify");
    EXPECT_EQ(p.mode, "single");
}
