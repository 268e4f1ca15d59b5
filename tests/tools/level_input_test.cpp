// Levels and probe lists that used to bake into something else than what they said (issue
// 34): two list entries of one name (the second silently overrode the first), a priority
// past 2^31 (wrapped), a misspelt member ("blend_distanse", ignored), a probe outside its
// own proxy box, more probes than the runtime draws in one view (kMaxLevelProbes: baked, then
// refused by every view), and a shard list without shards (merged into a level with empty
// checksums). Each is refused at bake time with one line naming the file and the field, and
// nothing is written.
#include "support/shell_tool.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";

using nlohmann::json;
using specula::test::lineCount;
using specula::test::shellQuote;
using specula::test::TempDir;
using specula::test::ToolRun;

ToolRun cook(const std::string& args) {
    return specula::test::runShellTool(kCook, args);
}

// Bakes the two-room level with `list` as --probes into DIR/level; the run's result.
ToolRun bakeWithList(const TempDir& dir, const json& list) {
    const fs::path file = dir.path / "probes.json";
    std::ofstream(file) << list.dump(2);
    return cook("bake " + shellQuote(specula::test::kTwoRooms) + " --face-res 8 --probes " +
                shellQuote(file.string()) + " --out " + shellQuote((dir.path / "level").string()));
}

// Refused with exit 1 and one line naming `file` and every one of `names`; nothing baked.
void expectRefused(const ToolRun& r, const fs::path& dir, const std::string& file,
                   std::initializer_list<std::string> names) {
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    for (const std::string& n : names)
        EXPECT_NE(r.err.find(n), std::string::npos) << "must name " << n << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir / "level" / "level.json")) << r.err;
}

json probe(const std::string& name, double x, json members = json::object()) {
    members["name"] = name;
    members["position"] = {x, 1.5, 1.0};
    return members;
}

} // namespace

TEST(LevelInput, TwoListEntriesOfOneNameAreRefusedNamingBoth) {
    const TempDir dir("level-input-names");
    const json list = {{"probes", {probe("hall", -4.0), probe("desk", -2.0), probe("hall", -1.0)}}};
    expectRefused(bakeWithList(dir, list), dir.path, (dir.path / "probes.json").string(),
                  {"probes[2].name", "probes[0]", "\"hall\""});
}

TEST(LevelInput, APriorityOutsideIntIsRefused) {
    const TempDir dir("level-input-priority");
    // 2^32 wrapped to 0, 2^31 to -2^31: the blend order was not the one written.
    for (const json& p : {json(4294967296LL), json(2147483648LL), json(-2147483649LL),
                          json(18446744073709551615ULL)}) {
        const json list = {{"probes", {probe("p", -4.0, {{"priority", p}})}}};
        expectRefused(bakeWithList(dir, list), dir.path, "probes.json",
                      {"probes[0].priority", p.dump()});
    }
    const json edge = {{"probes", {probe("p", -4.0, {{"priority", 2147483647LL}})}}};
    EXPECT_EQ(bakeWithList(dir, edge).status, 0) << "the largest int is a priority";
}

TEST(LevelInput, AnUnknownMemberIsRefusedNamingTheKeyAndTheFile) {
    const TempDir dir("level-input-keys");
    expectRefused(bakeWithList(dir, {{"probes", {probe("p", -4.0, {{"blend_distanse", 1.0}})}}}),
                  dir.path, "probes.json", {"probes[0].blend_distanse", "unknown member"});
    expectRefused(
        bakeWithList(
            dir, {{"probes",
                   {probe("p", -4.0,
                          {{"proxy",
                            {{"min", {-1, -1, -1}}, {"max", {1, 1, 1}}, {"maxx", {2, 2, 2}}}}})}}}),
        dir.path, "probes.json", {"probes[0].proxy.maxx"});
    expectRefused(
        bakeWithList(
            dir,
            {{"probes",
              {probe("p", -4.0,
                     {{"influence", {{"sphere", {{"radius", 1}, {"centre", {0, 0, 0}}}}}}})}}}),
        dir.path, "probes.json", {"probes[0].influence.sphere.centre"});
    // In the scene's markup too: the scene file and the node are named.
    const fs::path scenes = dir.path / "scene";
    fs::copy(fs::path(specula::test::kTwoRooms).parent_path(), scenes);
    const fs::path scene = scenes / "two_rooms.gltf";
    json gltf = json::parse(std::ifstream(scene));
    for (json& node : gltf["nodes"])
        if (node.value("name", "") == "room_b_probe")
            node["extras"]["specula_probe"]["priorty"] = 2;
    std::ofstream(scene) << gltf.dump();
    expectRefused(cook("bake " + shellQuote(scene.string()) + " --face-res 8 --out " +
                       shellQuote((dir.path / "level").string())),
                  dir.path, scene.string(), {"nodes[room_b_probe].extras.specula_probe.priorty"});
}

TEST(LevelInput, AProbeOutsideItsOwnProxyIsRefused) {
    const TempDir dir("level-input-proxy");
    // The proxy is relative to the probe: this box lies wholly above it.
    const json box = {{"min", {-1, 0.5, -1}}, {"max", {1, 2, 1}}};
    expectRefused(bakeWithList(dir, {{"probes", {probe("high", -3.0, {{"proxy", box}})}}}),
                  dir.path, "probes.json", {"probes[0].proxy", "probe high", "outside"});
}

TEST(LevelInput, MoreProbesThanTheRuntimeDrawsAreRefusedBeforeAnyBake) {
    const TempDir dir("level-input-cap");
    // The scene's two and 63 listed: 65, one more than a view holds (kMaxLevelProbes = 64).
    json probes = json::array();
    for (int i = 0; i < 63; ++i) {
        std::string name = "p"; // (not "p" + to_string: GCC 12's -Wrestrict false positive)
        name += std::to_string(i);
        probes.push_back(probe(name, -5.5 + 0.08 * i));
    }
    expectRefused(bakeWithList(dir, {{"probes", probes}}), dir.path, "probes.json",
                  {"probes", "65", "64"});
}

TEST(LevelInput, AShardListWithoutShardsIsNotMerged) {
    const TempDir dir("level-input-shards");
    const fs::path level = dir.path / "level", listFile = level / ".shards" / "shards.json";
    ASSERT_EQ(cook("shards " + shellQuote(specula::test::kTwoRooms) + " --face-res 8 --out " +
                   shellQuote(level.string()))
                  .status,
              0);
    const json list = json::parse(std::ifstream(listFile));
    const auto refusedWith = [&](json edited, const std::string& field) {
        std::ofstream(listFile) << edited.dump(2);
        const ToolRun r = cook("merge " + shellQuote(level.string()));
        EXPECT_EQ(r.status, 1) << field << "\n" << r.err;
        EXPECT_EQ(lineCount(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find(listFile.string() + ": " + field), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(level / "level.json")) << field;
        const ToolRun shard = cook("bake-shard " + shellQuote(level.string()) + " --shard 0");
        EXPECT_EQ(shard.status, 1) << field << "\n" << shard.err;
    };
    json noShards = list;
    noShards["shards"] = json::array();
    refusedWith(noShards, "shards");
    json noProbes = noShards;
    noProbes["level"]["probes"] = json::array();
    refusedWith(noProbes, "level.probes");
    json oneProbeLess = list;
    oneProbeLess["shards"].erase(1);
    refusedWith(oneProbeLess, "shards");
}
