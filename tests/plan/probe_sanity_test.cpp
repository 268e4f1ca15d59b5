// Degenerate probe placements (issue 10): measured with Embree from the probe centre, refused
// where a bake means nothing, warned where it is merely suspicious.
#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "assetcooker/lib/flavours/lightfield/lightfield_bake.h"
#include "assetcooker/lib/scene/probe_sanity.h"
#include "engine/core/error.h"
#include "plan/code_scene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace specula;

namespace {

// A closed room of single-sided quads facing in (8 x 4 x 8, floor at y = 0), a solid column
// (a box facing out) and optionally a mirror and a probe node.
struct Room : test::CodeScene {
    // A box [lo, hi]; inward: its faces look into it (a room), else out of it (a solid).
    static std::shared_ptr<MeshData> box(glm::vec3 lo, glm::vec3 hi, bool inward) {
        auto m = std::make_shared<MeshData>();
        for (int i = 0; i < 8; ++i)
            m->positions.push_back(
                glm::vec3((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z));
        // Counter-clockwise seen from outside.
        const unsigned quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                      {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& q : quads) {
            const unsigned tri[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
            for (int k = 0; k < 6; ++k)
                m->indices.push_back(tri[inward ? 5 - k : k]);
        }
        m->boundsMin = lo;
        m->boundsMax = hi;
        return m;
    }
    // `scale` scales the whole scene about the origin (0: every vertex on one point).
    explicit Room(float scale = 1.f, bool doubleSided = false) {
        material->doubleSided = doubleSided;
        node("room", glm::vec3(0.f), box({-4, 0, -4}, {4, 4, 4}, true), "", scale);
        node("column", scale * glm::vec3(2.5f, 0, 2.5f),
             box({-0.15f, 0, -0.15f}, {0.15f, 3, 0.15f}, false), "", scale);
    }
    void addMirrorAndProbe(glm::vec3 at) {
        node("mirror", at, box(glm::vec3(-0.2f), glm::vec3(0.2f), false),
             "{\"specula_reflector\": true}");
        node("probe", at, nullptr, "{\"specula_probe\": {\"cell_size\": 1.0}}");
    }
    SceneMarkup markup() {
        updateWorldTransforms(reg);
        return readSceneMarkup(reg, scene, "room.gltf");
    }
};

// The Error message `f` throws, or "" when it returns.
template <class F> std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

// The Error message of checkProbePlacement, or "" when it accepts.
std::string refusal(Room& r, glm::vec3 centre, bool sky = false) {
    const SceneMarkup m = r.markup();
    return errorOf([&] { checkProbePlacement(r.reg, m, centre, sky); });
}

} // namespace

TEST(ProbeSanity, InsideTheRoomIsFine) {
    Room r;
    const SceneMarkup m = r.markup();
    const ProbePlacement p = measureProbePlacement(r.reg, m, glm::vec3(0, 1.2f, 0));
    EXPECT_EQ(p.hits, p.directions);
    EXPECT_EQ(p.backHits, 0);
    EXPECT_TRUE(checkProbePlacement(r.reg, m, glm::vec3(0, 1.2f, 0), false).empty());
}

TEST(ProbeSanity, OutsideAClosedRoomIsRefused) {
    // --probe 100,0,0 on the bundled room: only the backs of its walls are in view.
    Room r;
    const std::string e = refusal(r, glm::vec3(100, 2, 0));
    EXPECT_NE(e.find("probe centre (100, 2, 0)"), std::string::npos) << e;
    EXPECT_NE(e.find("back faces of 'room' in 100 %"), std::string::npos) << e;
    // With a sky too: the sky does not make the backs of walls a meaningful bake.
    EXPECT_NE(refusal(r, glm::vec3(100, 2, 0), true), "");
}

TEST(ProbeSanity, InsideASolidColumnIsRefused) {
    Room r;
    r.addMirrorAndProbe(glm::vec3(2.5f, 1.f, 2.5f)); // a specula_probe node inside the column
    const std::string e = refusal(r, glm::vec3(2.5f, 1.f, 2.5f));
    EXPECT_NE(e.find("nodes[probe].extras.specula_probe"), std::string::npos) << e;
    EXPECT_NE(e.find("back faces of 'column' in 100 %"), std::string::npos) << e;
    EXPECT_NE(e.find("inside a solid"), std::string::npos) << e;
}

TEST(ProbeSanity, OnASurfaceIsRefusedAndNearOneWarned) {
    Room r;
    // On the floor (and in the plane of a wall, as --probe 4,1,0 is in the bundled room).
    for (glm::vec3 c : {glm::vec3(0, 0, 0), glm::vec3(4, 1, 0)}) {
        const std::string e = refusal(r, c);
        EXPECT_NE(e.find("lies on a surface"), std::string::npos) << e;
        EXPECT_EQ(e.find("-0 m"), std::string::npos) << e;
    }
    // A millimetre above the floor of a 12 m scene: bakeable, but said.
    const SceneMarkup m = r.markup();
    const auto w = checkProbePlacement(r.reg, m, glm::vec3(0, 1e-3f, 0), false);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("nearest environment surface is only 0.001 m away"), std::string::npos)
        << w[0];
}

// Two nodes 3e38 m away (issue 34): the bounds of every node overflowed float ("scene size
// inf") and dwarfed the room, so a probe 1.2 m from the floor "lay on a surface". The scale
// is now what the probe sees: the room is judged as if the far nodes were not there.
TEST(ProbeSanity, FarNodesDoNotShrinkTheRoomAroundTheProbe) {
    Room r;
    const auto speck = Room::box(glm::vec3(-0.1f), glm::vec3(0.1f), false);
    r.node("far_east", glm::vec3(3e38f, 1, 0), speck);
    r.node("far_west", glm::vec3(-3e38f, 1, 0), speck);
    const SceneMarkup m = r.markup();
    const ProbePlacement p = measureProbePlacement(r.reg, m, glm::vec3(0, 1.2f, 0));
    EXPECT_TRUE(std::isfinite(p.sceneSize));
    EXPECT_LT(p.sceneSize, 20.0); // twice the farthest corner of the 8 x 4 x 8 room
    EXPECT_GT(p.sceneSize, 8.0);
    EXPECT_TRUE(checkProbePlacement(r.reg, m, glm::vec3(0, 1.2f, 0), false).empty());
    // The floor is still a surface, and the message names finite sizes.
    const std::string e = refusal(r, glm::vec3(0, 0, 0));
    EXPECT_NE(e.find("lies on a surface"), std::string::npos) << e;
    EXPECT_EQ(e.find("inf"), std::string::npos) << e;
}

TEST(ProbeSanity, DoubleSidedBackFacesAreLegitimate) {
    // The same room outside, its walls doubleSided: their outsides are surfaces, so no refusal;
    // the probe still looks at the scene from afar, which is warned.
    Room r(1.f, true);
    const SceneMarkup m = r.markup();
    std::vector<std::string> w;
    ASSERT_NO_THROW(w = checkProbePlacement(r.reg, m, glm::vec3(100, 2, 0), true));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("outside the bounds of all environment geometry"), std::string::npos)
        << w[0];
}

TEST(ProbeSanity, SomeBackFacesWarn) {
    // A 2 m single-sided board half a metre away, facing away from the probe: about 30 % of
    // the view is its back. Suspicious, not meaningless.
    Room r;
    auto board = std::make_shared<MeshData>();
    board->positions = {{-1, 0, 0}, {1, 0, 0}, {1, 2, 0}, {-1, 2, 0}};
    board->indices = {0, 1, 2, 0, 2, 3}; // front towards +z, the probe at z = -0.5
    r.node("board", glm::vec3(0, 0.2f, 0), board);
    const SceneMarkup m = r.markup();
    const ProbePlacement p = measureProbePlacement(r.reg, m, glm::vec3(0, 1.2f, -0.5f));
    const double share = double(p.backHits) / double(p.hits);
    EXPECT_GT(share, 0.1);
    EXPECT_LT(share, 0.5);
    const auto w = checkProbePlacement(r.reg, m, glm::vec3(0, 1.2f, -0.5f), false);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("back faces of 'board'"), std::string::npos) << w[0];
}

TEST(ProbeSanity, ScaledScenesMeasureTheSame) {
    // The room scaled by 1e6 and by 1e-6, the probe scaled with it: neither is on a surface
    // nor anything else; the checks are relative to the scene's size.
    for (float s : {1e6f, 1e-6f}) {
        Room r(s);
        const SceneMarkup m = r.markup();
        const ProbePlacement p = measureProbePlacement(r.reg, m, glm::vec3(0, 1.2f * s, 0));
        EXPECT_EQ(p.hits, p.directions) << s;
        EXPECT_EQ(p.backHits, 0) << s;
        EXPECT_TRUE(checkProbePlacement(r.reg, m, glm::vec3(0, 1.2f * s, 0), false).empty()) << s;
    }
}

namespace {

// Both flavours on the same scene: the error text of each ("" when it bakes).
struct BothBakes {
    std::string distance, lightField;
};
BothBakes bakeBoth(Room& r, glm::vec3 centre, const Image* sky) {
    const SceneMarkup m = r.markup();
    BothBakes out;
    DistanceBakeOptions d;
    d.centre = centre;
    d.faceRes = 8;
    d.sky = sky;
    out.distance = errorOf([&] { bakeDistanceProbe(r.reg, m, d); });
    LightFieldBakeOptions l;
    l.cellCentre = centre;
    l.cellSize = 1.f;
    l.cameras = 2;
    l.res = 4;
    l.sky = sky;
    out.lightField = errorOf([&] { bakeLightFieldProbe(r.reg, m, l); });
    return out;
}

Image greySky() {
    Image sky(8, 4, 3);
    for (float& v : sky.pixels)
        v = 0.5f;
    return sky;
}

// A scene of a mirror and a probe node alone.
struct Empty : Room {
    Empty() : Room() {
        scene.entities.clear();
        scene.roots.clear();
        reg = ecs::Registry();
        addMirrorAndProbe(glm::vec3(0, 1, 0));
    }
};

} // namespace

TEST(ProbeSanity, NothingToReflectIsRefusedByBothFlavours) {
    // The reflector as the only mesh, no sky: the light-field bake refused, the distance bake
    // baked black. Now both refuse with the same message.
    Empty r;
    const BothBakes b = bakeBoth(r, glm::vec3(0, 1, 0), nullptr);
    EXPECT_NE(b.distance.find("nothing to reflect: the scene has no environment geometry"),
              std::string::npos)
        << b.distance;
    EXPECT_EQ(b.distance, b.lightField);
    // A sky and no geometry (assets/sky_only): both bake, the light field all sky.
    const Image sky = greySky();
    const BothBakes withSky = bakeBoth(r, glm::vec3(0, 1, 0), &sky);
    EXPECT_EQ(withSky.distance, "");
    EXPECT_EQ(withSky.lightField, "");
}

TEST(ProbeSanity, DegenerateGeometryIsNothingToReflect) {
    // The room scaled by 0: every triangle degenerate, nothing can be hit.
    Room r(0.f);
    r.addMirrorAndProbe(glm::vec3(0, 1, 0));
    const BothBakes b = bakeBoth(r, glm::vec3(0, 1, 0), nullptr);
    EXPECT_NE(b.distance.find("none of 4096 directions from the probe, nor a ray aimed at each of "
                              "its 2 objects, meets environment geometry"),
              std::string::npos)
        << b.distance;
    EXPECT_EQ(b.distance, b.lightField);
    const Image sky = greySky();
    const SceneMarkup m = r.markup();
    const auto w = checkProbePlacement(r.reg, m, glm::vec3(0, 1, 0), true);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("the probe holds the sky alone"), std::string::npos) << w[0];
    EXPECT_EQ(bakeBoth(r, glm::vec3(0, 1, 0), &sky).lightField, "");
}

TEST(ProbeSanity, SmallFarObjectsAreNotNothing) {
    // Pebbles a kilometre away slip between the spread directions; the rays aimed at them find
    // them, so the bake is allowed (with a warning) rather than refused as empty.
    test::CodeScene s;
    const auto pebble = Room::box(glm::vec3(-0.1f), glm::vec3(0.1f), false);
    for (int i = 0; i < 8; ++i)
        s.node("pebble" + std::to_string(i),
               1000.f * glm::vec3(std::cos(0.8f * float(i)), 0.1f, std::sin(0.8f * float(i))),
               pebble);
    updateWorldTransforms(s.reg);
    const SceneMarkup m = readSceneMarkup(s.reg, s.scene, "pebbles.gltf");
    const ProbePlacement p = measureProbePlacement(s.reg, m, glm::vec3(0.f));
    EXPECT_EQ(p.hits, 0);
    EXPECT_EQ(p.aimedHits, 8);
    std::vector<std::string> w;
    ASSERT_NO_THROW(w = checkProbePlacement(s.reg, m, glm::vec3(0.f), false));
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("covers under 1/4096 of the view"), std::string::npos) << w[0];
}

TEST(ProbeSanity, BakesRefuseAPlacementAndReturnItsWarnings) {
    Room r;
    std::vector<std::string> warnings;
    const SceneMarkup m = r.markup();
    DistanceBakeOptions d;
    d.centre = glm::vec3(0, 1e-3f, 0);
    d.faceRes = 8;
    d.warnings = &warnings;
    bakeDistanceProbe(r.reg, m, d);
    LightFieldBakeOptions l;
    l.cellCentre = d.centre;
    l.cameras = 2;
    l.res = 4;
    l.warnings = &warnings;
    bakeLightFieldProbe(r.reg, m, l);
    ASSERT_EQ(warnings.size(), 2u);
    EXPECT_EQ(warnings[0], warnings[1]);
    d.centre = l.cellCentre = glm::vec3(2.5f, 1.f, 2.5f);
    EXPECT_THROW(bakeDistanceProbe(r.reg, m, d), Error);
    EXPECT_THROW(bakeLightFieldProbe(r.reg, m, l), Error);
}

TEST(SceneMarkup, NonPositiveCellSizeIsRefusedNamingNodeAndField) {
    for (const char* bad : {"-2", "0", "\"big\"", "1e5", "null"}) {
        Room r;
        r.node("probe", glm::vec3(0, 1, 0), nullptr,
               std::string("{\"specula_probe\": {\"cell_size\": ") + bad + "}}");
        updateWorldTransforms(r.reg);
        try {
            readSceneMarkup(r.reg, r.scene, "room.gltf");
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("room.gltf"), std::string::npos) << what;
            EXPECT_NE(what.find("nodes[probe].extras.specula_probe.cell_size"), std::string::npos)
                << what;
        }
    }
    Room ok;
    ok.addMirrorAndProbe(glm::vec3(0, 1, 0));
    EXPECT_EQ(markupCellSize(ok.markup()), 1.f);
}
