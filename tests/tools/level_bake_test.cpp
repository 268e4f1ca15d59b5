// Baking a level (level_bake.h) on the bundled two-room scene (assets/two_rooms: rooms A and B
// joined by a doorway in the wall x = 0, one probe each): every probe gets its folder and an
// index entry; a re-run re-bakes nothing; moving an object only room B's probe can see
// re-bakes that probe alone and says why; a failure half-way leaves the probes baked before
// it intact and indexed; bad probe lists are errors naming the file and field. The default
// proxy is the room a probe stands in, also on a box room written here with a cupboard in
// front of the probe.
#include "assetcooker/lib/level/level_bake.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/scene/components.h"
#include "engine/scene/transform_system.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <array>
#include <fstream>
#include <sstream>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;

const std::string kTwoRooms = std::string(SPECULA_SOURCE_DIR) + "/assets/two_rooms/two_rooms.gltf";

// Room A's inner box (inside faces of its walls, floor and ceiling), as the scene's script
// lays it out: x -5.95 .. -0.05, y 0 .. 3, z -2.95 .. 2.95.
const Aabb kRoomA{glm::vec3(-5.95f, 0.f, -2.95f), glm::vec3(-0.05f, 3.f, 2.95f)};

class LevelBake : public test::ScratchDirTest {
protected:
    LevelBake() : ScratchDirTest("specula-level") {}

    LevelCookOptions options(int faceRes = 16) const {
        LevelCookOptions o;
        o.cook.scene = kTwoRooms;
        o.cook.out = (root_ / "level").string();
        DistanceCookSettings d;
        d.faceRes = faceRes;
        d.planned = false;
        o.cook.flavour = d;
        o.cook.progress = false;
        return o;
    }

    std::string writeProbeList(const std::string& text) const {
        const std::string path = (root_ / "probes.json").string();
        std::ofstream(path) << text;
        return path;
    }

    static void moveNode(ProbeScene& scene, const std::string& name, glm::vec3 by) {
        for (ecs::Entity e : scene.loaded.entities)
            if (const Name* n = scene.registry.find<Name>(e); n && n->value == name)
                scene.registry.get<Transform>(e).translation += by;
        updateWorldTransforms(scene.registry);
    }
};

void expectBoxNear(const Aabb& got, const Aabb& want, float tolerance) {
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(got.min[a], want.min[a], tolerance) << "min axis " << a;
        EXPECT_NEAR(got.max[a], want.max[a], tolerance) << "max axis " << a;
    }
}

// The unit cube centred at the origin as 36 vertices, counter-clockwise seen from outside
// (outward: a solid box) or from inside (inward: a room's walls, floor and ceiling).
std::vector<glm::vec3> unitCube(bool outward) {
    std::vector<glm::vec3> v;
    for (int axis = 0; axis < 3; ++axis)
        for (const float sign : {1.f, -1.f}) {
            std::array<glm::vec3, 4> c{};
            const float uv[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
            for (int i = 0; i < 4; ++i) {
                c[i][axis] = 0.5f * sign;
                c[i][(axis + 1) % 3] = 0.5f * uv[i][0];
                c[i][(axis + 2) % 3] = 0.5f * uv[i][1];
            }
            for (const std::array<int, 3> t : {std::array<int, 3>{0, 1, 2}, {0, 2, 3}}) {
                glm::vec3 a = c[t[0]], b = c[t[1]], d = c[t[2]];
                if ((glm::dot(glm::cross(b - a, d - a), a + b + d) > 0.f) != outward)
                    std::swap(b, d);
                v.insert(v.end(), {a, b, d});
            }
        }
    return v;
}

// DIR/room.gltf: the closed room `room` (faces inward) holding the solid boxes `solids`, each
// a node stretching the unit cube over its box; no markup.
std::string writeBoxRoom(const fs::path& dir, const Aabb& room, const std::vector<Aabb>& solids) {
    std::vector<glm::vec3> positions = unitCube(false);
    const std::vector<glm::vec3> outward = unitCube(true);
    positions.insert(positions.end(), outward.begin(), outward.end());
    const std::size_t bytes = positions.size() * sizeof(glm::vec3);
    std::ofstream(dir / "room.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(positions.data()), std::streamsize(bytes));
    using nlohmann::json;
    json nodes = json::array(), roots = json::array();
    for (std::size_t i = 0; i <= solids.size(); ++i) {
        const Aabb& b = i == 0 ? room : solids[i - 1];
        const glm::vec3 c = b.centre(), e = b.extent();
        nodes.push_back({{"name", i == 0 ? "room" : "solid_" + std::to_string(i)},
                         {"mesh", i == 0 ? 0 : 1},
                         {"translation", {c.x, c.y, c.z}},
                         {"scale", {e.x, e.y, e.z}}});
        roots.push_back(i);
    }
    auto accessor = [](std::size_t offset) {
        return json{{"bufferView", 0},       {"byteOffset", offset}, {"componentType", 5126},
                    {"count", 36},           {"type", "VEC3"},       {"min", {-0.5, -0.5, -0.5}},
                    {"max", {0.5, 0.5, 0.5}}};
    };
    auto mesh = [](int a) { return json{{"primitives", {{{"attributes", {{"POSITION", a}}}}}}}; };
    const json gltf = {{"asset", {{"version", "2.0"}}},
                       {"scene", 0},
                       {"scenes", {{{"nodes", roots}}}},
                       {"nodes", nodes},
                       {"meshes", {mesh(0), mesh(1)}},
                       {"buffers", {{{"uri", "room.bin"}, {"byteLength", bytes}}}},
                       {"bufferViews", {{{"buffer", 0}, {"byteLength", bytes}}}},
                       {"accessors", {accessor(0), accessor(36 * sizeof(glm::vec3))}}};
    std::ofstream(dir / "room.gltf") << gltf.dump();
    return (dir / "room.gltf").string();
}

TEST_F(LevelBake, GathersEveryProbeOfTheMarkupWithItsVolumes) {
    ProbeScene scene(kTwoRooms, "");
    const GatheredProbes g = gatherLevelProbes(scene, {});
    ASSERT_EQ(g.probes.size(), 2u);
    EXPECT_EQ(g.probes[0].name, "room_a_probe");
    EXPECT_EQ(g.probes[1].name, "room_b_probe");
    expectBoxNear(g.probes[0].proxy, kRoomA, 1e-4f);
    // The influence reaches 0.5 m past the doorway wall into room B.
    EXPECT_NEAR(g.probes[0].influence.box.max.x, 0.55f, 1e-4f);
    EXPECT_NEAR(g.probes[1].influence.box.min.x, -0.55f, 1e-4f);
    EXPECT_TRUE(g.warnings.empty()) << g.warnings.front();
}

TEST_F(LevelBake, AProbeWithoutAProxyGetsTheRoomItStandsIn) {
    // A probe of the list with a position only, in room A: its proxy is room A's closed-form
    // inside box, though a tenth of its rays towards +x pass the doorway into room B and
    // room A's table fills part of its view down.
    ProbeScene scene(kTwoRooms, "");
    LevelProbeSources s;
    s.file = writeProbeList(R"({"probes": [{"name": "extra", "position": [-2.5, 1.5, 1.2]}]})");
    const GatheredProbes g = gatherLevelProbes(scene, s);
    ASSERT_EQ(g.probes.size(), 3u);
    const ProbeVolume& extra = g.probes[2];
    EXPECT_EQ(extra.name, "extra");
    expectBoxNear(extra.proxy, kRoomA, 2e-3f);
    // Its influence (not stated) is the proxy grown by the blend distance (0.5 m), cut
    // half-way to room A's probe at (-3, 1.2, 0), inside the same room: they lie furthest
    // apart along z (1.2 m), so the cut is at z = 0.6, less the blend distance.
    Aabb cut{extra.proxy.min - glm::vec3(0.5f), extra.proxy.max + glm::vec3(0.5f)};
    cut.min.z = 0.1f;
    expectBoxNear(extra.influence.box, cut, 1e-5f);
}

TEST_F(LevelBake, FurnitureInFrontOfAProbeLeavesItsProxyTheRoom) {
    // A 6 x 3 x 6 m room and a probe 1.5 m up in its middle, a cupboard 1 m in front of it
    // along +x (x 1 .. 1.6, up to 1.7 m, 1 m wide): the axis ray towards +x meets the
    // cupboard, yet the proxy reaches the room's wall at x = 3 on that side as on the others
    // (the wall fills a good part of the view past the cupboard), each side on its wall's
    // plane up to float precision.
    const Aabb room{glm::vec3(-3.f, 0.f, -3.f), glm::vec3(3.f, 3.f, 3.f)};
    const Aabb cupboard{glm::vec3(1.f, 0.f, -0.5f), glm::vec3(1.6f, 1.7f, 0.5f)};
    ProbeScene scene(writeBoxRoom(root_, room, {cupboard}), "");
    LevelProbeSources s;
    s.file = writeProbeList(R"({"probes": [{"name": "middle", "position": [0, 1.5, 0]}]})");
    const GatheredProbes g = gatherLevelProbes(scene, s);
    ASSERT_EQ(g.probes.size(), 1u);
    expectBoxNear(g.probes[0].proxy, room, 1e-5f);
    // The influence is the room grown by the blend distance: a reflector anywhere in the
    // room, even touching the wall or the cupboard, takes nothing from the sky.
    expectBoxNear(g.probes[0].influence.box,
                  Aabb{room.min - glm::vec3(0.5f), room.max + glm::vec3(0.5f)}, 1e-5f);
    for (const glm::vec3 p : {glm::vec3(2.95f, 0.05f, 2.95f), glm::vec3(0.f, 1.75f, 0.f)})
        EXPECT_EQ(influenceWeight(g.probes[0], p), 1.f);
    EXPECT_TRUE(g.warnings.empty()) << g.warnings.front();

    // The same probe in the empty room gets the room's box.
    ProbeScene empty(writeBoxRoom(root_, room, {}), "");
    expectBoxNear(gatherLevelProbes(empty, s).probes[0].proxy, room, 1e-5f);
}

TEST_F(LevelBake, ARowOfProbesInOneRoomSharesItsInfluenceOut) {
    // Three probes along x in room A, stated by position only: each influence ends one blend
    // distance (1 m, stated) past the half-way point to its neighbours.
    ProbeScene scene(kTwoRooms, "");
    LevelProbeSources s;
    s.file = writeProbeList(R"({"probes": [
        {"name": "west", "position": [-5, 1.5, -1.2], "blend_distance": 1},
        {"name": "middle", "position": [-3, 1.5, -1.2], "blend_distance": 1},
        {"name": "east", "position": [-1, 1.5, -1.2], "blend_distance": 1}]})");
    const GatheredProbes g = gatherLevelProbes(scene, s);
    ASSERT_EQ(g.probes.size(), 5u);
    const ProbeVolume &west = g.probes[2], &middle = g.probes[3], &east = g.probes[4];
    EXPECT_NEAR(west.influence.box.max.x, -4.f + 1.f, 1e-5f);
    EXPECT_NEAR(middle.influence.box.min.x, -4.f - 1.f, 1e-5f);
    EXPECT_NEAR(middle.influence.box.max.x, -2.f + 1.f, 1e-5f);
    EXPECT_NEAR(east.influence.box.min.x, -2.f - 1.f, 1e-5f);
    // Along the row, more than a blend distance from the room's walls (room A's own probe
    // stands 1.2 m off the row and keeps its stated influence), the engine's blend of the three
    // leaves nothing to the sky: wherever one probe fades, its neighbour weighs 1.
    const std::vector<ProbeVolume> row{west, middle, east};
    for (float x = -4.75f; x <= -1.25f; x += 0.125f) {
        const ProbeBlend b = blendProbes(row, glm::vec3(x, 1.5f, -1.2f), 4);
        EXPECT_NEAR(b.sky, 0.f, 1e-6f) << "x = " << x;
    }
    EXPECT_EQ(influenceWeight(west, glm::vec3(-1, 1.5f, -1.2f)), 0.f);
}

TEST_F(LevelBake, BakesEveryProbeThenOnlyWhatChangedAndSaysWhy) {
    ProbeScene scene(kTwoRooms, "");
    std::ostringstream log;
    const LevelCookResult first = cookLevel(scene, options(), &log);
    ASSERT_EQ(first.probes.size(), 2u);
    for (const LevelProbeOutcome& p : first.probes) {
        EXPECT_TRUE(p.baked);
        EXPECT_EQ(p.reason, "new");
    }
    const LevelIndex index = readLevelIndex(first.index);
    ASSERT_EQ(index.probes.size(), 2u);
    EXPECT_EQ(index.flavour, "distance");
    for (const LevelProbeEntry& e : index.probes) {
        const fs::path manifest = root_ / "level" / e.folder / "manifest.json";
        ASSERT_TRUE(fs::exists(manifest)) << manifest;
        EXPECT_EQ(fileChecksum(manifest.string()), e.manifestChecksum);
    }
    // Each probe's asset is centred on its own room and boxes its own proxy.
    const DistanceProbeAsset a =
        readDistanceProbe((root_ / "level/room_b_probe/manifest.json").string());
    EXPECT_NEAR(a.centre.x, 3.f, 1e-5f);
    EXPECT_NEAR(a.boxMin.x + a.centre.x, 0.05f, 1e-4f);

    // Nothing changed: nothing re-baked, the folders untouched.
    const auto stamp = fs::last_write_time(root_ / "level/room_a_probe/manifest.json");
    const LevelCookResult again = cookLevel(scene, options(), &log);
    for (const LevelProbeOutcome& p : again.probes) {
        EXPECT_FALSE(p.baked) << p.name;
        EXPECT_EQ(p.reason, "up to date");
    }
    EXPECT_EQ(fs::last_write_time(root_ / "level/room_a_probe/manifest.json"), stamp);

    // Room B's crate stands against the wall beside the doorway, where room A's probe cannot
    // see it: moving it re-bakes room B's probe only.
    moveNode(scene, "room_b_crate", glm::vec3(0.4f, 0.f, -0.3f));
    const LevelCookResult moved = cookLevel(scene, options(), &log);
    ASSERT_EQ(moved.probes.size(), 2u);
    EXPECT_FALSE(moved.probes[0].baked) << moved.probes[0].reason;
    EXPECT_TRUE(moved.probes[1].baked);
    EXPECT_EQ(moved.probes[1].reason, "geometry changed");
    EXPECT_EQ(fs::last_write_time(root_ / "level/room_a_probe/manifest.json"), stamp);
    EXPECT_NE(log.str().find("probe room_b_probe: baked in"), std::string::npos) << log.str();

    // A reflector made rough by its markup alone (the materials unchanged) re-bakes both
    // probes: under --glossy auto that decides whether their chains are baked.
    ASSERT_FALSE(scene.markup.reflectors.empty());
    scene.markup.reflectors.front().roughness = 0.3f;
    const LevelCookResult rough = cookLevel(scene, options(), &log);
    for (const LevelProbeOutcome& p : rough.probes) {
        EXPECT_TRUE(p.baked) << p.name;
        EXPECT_EQ(p.reason, "geometry changed");
    }

    // Other options re-bake both, naming the options.
    const LevelCookResult resized = cookLevel(scene, options(8), &log);
    for (const LevelProbeOutcome& p : resized.probes) {
        EXPECT_TRUE(p.baked);
        EXPECT_EQ(p.reason, "options changed");
    }
}

// Verify, never trust (issue 34): the manifest's checksum alone says nothing of the layer
// files it lists. An edited layer and a deleted one re-bake their probes, saying which file.
TEST_F(LevelBake, AnEditedOrDeletedLayerFileReBakesItsProbeSayingWhy) {
    ProbeScene scene(kTwoRooms, "");
    cookLevel(scene, options(), nullptr);
    const fs::path edited = root_ / "level/room_a_probe/layer_00.ktx2";
    const fs::path deleted = root_ / "level/room_b_probe/layer_00.ktx2";
    ASSERT_TRUE(fs::exists(edited) && fs::exists(deleted));
    {
        std::fstream f(edited, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(fs::file_size(edited) / 2));
        f.put('X');
    }
    fs::remove(deleted);
    std::ostringstream log;
    const LevelCookResult again = cookLevel(scene, options(), &log);
    ASSERT_EQ(again.probes.size(), 2u);
    EXPECT_TRUE(again.probes[0].baked);
    EXPECT_EQ(again.probes[0].reason, "file layer_00.ktx2 altered on disk");
    EXPECT_TRUE(again.probes[1].baked);
    EXPECT_EQ(again.probes[1].reason, "file layer_00.ktx2 missing");
    EXPECT_NE(log.str().find("probe room_b_probe: baked in"), std::string::npos) << log.str();
    EXPECT_TRUE(fs::exists(deleted));
    // Re-baked, the level is whole again: a further run finds everything up to date.
    for (const LevelProbeOutcome& p : cookLevel(scene, options(), nullptr).probes)
        EXPECT_EQ(p.reason, "up to date") << p.name;
}

TEST_F(LevelBake, AFailureHalfWayLeavesTheProbesBakedBeforeItIndexed) {
    ProbeScene scene(kTwoRooms, "");
    // Room B's folder is taken by a file of the user's: its bake must refuse it, after room
    // A's probe was baked and committed.
    fs::create_directories(root_ / "level/room_b_probe");
    std::ofstream(root_ / "level/room_b_probe/notes.txt") << "mine";
    std::ofstream(root_ / "level/level.json")
        << R"({"format": "specula-level", "version": 1, "source": "x", "flavour": "distance",
              "probes": []})";
    EXPECT_THROW(cookLevel(scene, options(), nullptr), Error);
    EXPECT_TRUE(fs::exists(root_ / "level/room_b_probe/notes.txt"));
    const LevelIndex index = readLevelIndex((root_ / "level/level.json").string());
    ASSERT_EQ(index.probes.size(), 1u);
    EXPECT_EQ(index.probes[0].volume.name, "room_a_probe");
    EXPECT_EQ(fileChecksum((root_ / "level/room_a_probe/manifest.json").string()),
              index.probes[0].manifestChecksum);
}

TEST_F(LevelBake, RefusesAFolderThatIsNeitherEmptyNorALevel) {
    ProbeScene scene(kTwoRooms, "");
    fs::create_directories(root_ / "level");
    std::ofstream(root_ / "level/thesis.tex") << "mine";
    try {
        cookLevel(scene, options(), nullptr);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no level.json"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::exists(root_ / "level/thesis.tex"));
}

TEST_F(LevelBake, BadProbeListsAreErrorsNamingTheFileAndField) {
    ProbeScene scene(kTwoRooms, "");
    const auto errorOf = [&](const std::string& text) -> std::string {
        LevelProbeSources s;
        s.file = writeProbeList(text);
        try {
            gatherLevelProbes(scene, s);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    const std::string list = (root_ / "probes.json").string();
    EXPECT_EQ(errorOf(R"({"probes": [{"name": "x", "position": [0, 1, 0],
                        "influence": {"box": {"min": [0, 0, 0], "max": [-1, 1, 1]}}}]})"),
              list + ": probes[0].influence.box: zero-size or inverted box: every component "
                     "of min must lie below max");
    EXPECT_EQ(errorOf(R"({"probes": [{"name": "x"}]})"),
              list + ": probes[0].position: missing (a new probe needs a position)");
    EXPECT_NE(errorOf(R"({"probes": [{"name": "x", "position": [0, 1]}]})")
                  .find("probes[0].position: expected [x, y, z]"),
              std::string::npos);
    EXPECT_NE(errorOf(R"({"probes": 3})").find("probes: expected an array"), std::string::npos);
}

TEST_F(LevelBake, WarnsOfTwinProbesAndOfAProbeInsideSolidGeometry) {
    ProbeScene scene(kTwoRooms, "");
    LevelProbeSources s;
    // A twin of room A's probe (same volumes, same priority) and a probe inside room B's
    // column (a closed box).
    s.file = writeProbeList(R"({"probes": [
        {"name": "twin", "position": [-3, 1.2, 0], "proxy": {"min": [-2.95, -1.2, -2.95],
         "max": [2.95, 1.8, 2.95]}, "influence": {"box": {"min": [-2.95, -1.2, -2.95],
         "max": [3.55, 1.8, 2.95]}}},
        {"name": "buried", "position": [4.2, 1.0, -0.8]}]})");
    const GatheredProbes g = gatherLevelProbes(scene, s);
    std::string all;
    for (const std::string& w : g.warnings)
        all += w + "\n";
    EXPECT_NE(all.find("probes room_a_probe and twin have equal priority and identical volumes: "
                       "room_a_probe is blended first"),
              std::string::npos)
        << all;
    EXPECT_NE(all.find("probe buried lies inside solid geometry"), std::string::npos) << all;
    EXPECT_EQ(all.find("probe room_b_probe lies inside"), std::string::npos) << all;
}

} // namespace
} // namespace specula
