// A level's bake as shards (shard_bake.h) on the bundled two-room scene (two probes), what is
// refused: a merge with a shard (or a part) missing names it and writes nothing, and so does
// one with a part file truncated or with a wrong header, or a probe shard tampered with or
// swapped; a shard of a scene edited since the list is refused; an index out of range names
// the count; --shard-rows out of range is refused naming it; a damaged shard list is an Error
// naming the list. The sharded bake that works: shard_bake_test.cpp.
#include "assetcooker/lib/cli/cli.h"
#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/shard_checksum.h"
#include "engine/core/error.h"
#include "shard_bake_fixture.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;

using test::kTwoRooms;
using test::shard_bake::ShardBake;

TEST_F(ShardBake, APartMissingIsNamedByMergeAndByItsProbeShardAndNothingIsWritten) {
    ProbeScene scene(kTwoRooms, "");
    const ShardList list = writeShardList(scene, options("level", lightField()), nullptr);
    const std::string dir = (root_ / "level").string();
    for (int i = 0; i < int(list.shards.size()); ++i)
        if (i != 3 && shardDependencies(list, i).empty()) bakeShard(dir, i, nullptr);
    try {
        mergeShards(dir, nullptr);
        FAIL() << "merged with a part missing";
    } catch (const Error& e) {
        EXPECT_NE(
            std::string(e.what()).find(
                "1 of 14 shards not baked: 3 (probe room_a_probe, part 3: slab 3 rows 0 .. 1"),
            std::string::npos)
            << e.what();
    }
    try {
        bakeShard(dir, 6, nullptr);
        FAIL() << "assembled a probe with a part missing";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("6 part shards; 1 not baked: 3 (probe room_a_probe"),
                  std::string::npos)
            << e.what();
    }
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename(), ".shards") << e.path() << " written by a failed merge";
}

TEST_F(ShardBake, ATruncatedOrMislabelledPartIsRefusedNamingItsFileAndNothingIsMerged) {
    ProbeScene scene(kTwoRooms, "");
    const ShardList list = writeShardList(scene, options("level", lightField()), nullptr, 1);
    const std::string dir = (root_ / "level").string();
    for (int i = 0; i < int(list.shards.size()); ++i)
        if (shardDependencies(list, i).empty()) bakeShard(dir, i, nullptr);
    const std::string part = shardOutputPath(dir, list.shards[5]);
    std::ifstream in(part, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    in.close();
    std::string wrongHeader = bytes;
    wrongHeader.replace(0, 8, "NOTROWS!");
    for (const std::string& broken : {bytes.substr(0, bytes.size() / 2), wrongHeader}) {
        std::ofstream(part, std::ios::binary | std::ios::trunc) << broken;
        try {
            mergeShards(dir, nullptr);
            FAIL() << "merged a broken part";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), part) << e.what();
        }
        for (const auto& e : fs::directory_iterator(dir))
            EXPECT_EQ(e.path().filename(), ".shards") << e.path() << " written by a failed merge";
    }
}

// Verify, never trust (issue 34): a probe shard edited, truncated, swapped with another's or
// without its checksums is refused by the merge naming the shard and the file, and nothing is
// written; bake-shard bakes a shard without checksums again.
TEST_F(ShardBake, ATamperedTruncatedOrSwappedShardIsRefusedNamingTheShardAndFile) {
    ProbeScene scene(kTwoRooms, "");
    const ShardList list = writeShardList(scene, options("level", distance()), nullptr);
    const std::string dir = (root_ / "level").string();
    const auto bakeBoth = [&] {
        for (int i = 0; i < 2; ++i) {
            fs::remove_all(shardOutputPath(dir, list.shards[std::size_t(i)]));
            bakeShard(dir, i, nullptr);
        }
    };
    const fs::path layer = fs::path(shardOutputPath(dir, list.shards[0])) / "layer_00.ktx2";
    const auto expectRefused = [&](const fs::path& file, const std::string& why) {
        try {
            mergeShards(dir, nullptr);
            ADD_FAILURE() << "merged a broken store (" << why << ")";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), file.string()) << e.what();
            EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("shard 0 (probe room_a_probe, " +
                                                 list.shards[0].hash + ")"),
                      std::string::npos)
                << e.what();
        }
        for (const auto& e : fs::directory_iterator(dir))
            EXPECT_EQ(e.path().filename(), ".shards") << e.path() << " written by a failed merge";
    };
    bakeBoth();
    {
        std::fstream f(layer, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(std::streamoff(fs::file_size(layer) / 2));
        f.put('X');
    }
    expectRefused(layer, "altered or truncated");
    bakeBoth();
    fs::resize_file(layer, fs::file_size(layer) / 2);
    expectRefused(layer, "altered or truncated");
    bakeBoth();
    // Shard 0's folder and checksums under shard 1's name and back: each is whole, but not
    // the shard its name says.
    const fs::path a = shardOutputPath(dir, list.shards[0]),
                   b = shardOutputPath(dir, list.shards[1]);
    const fs::path sa = shardSumPath(dir, list.shards[0]), sb = shardSumPath(dir, list.shards[1]);
    for (const auto& [from, to] : {std::pair{a, root_ / "x"},
                                   {b, a},
                                   {root_ / "x", b},
                                   {sa, root_ / "y"},
                                   {sb, sa},
                                   {root_ / "y", sb}})
        fs::rename(from, to);
    expectRefused(sa, "swapped with another shard's");
    bakeBoth();
    fs::remove(sa);
    expectRefused(sa, "missing");
    EXPECT_FALSE(bakeShard(dir, 0, nullptr).skipped) << "a shard without checksums is re-baked";
    EXPECT_EQ(mergeShards(dir, nullptr).probes.size(), 2u);
}

TEST_F(ShardBake, AShardOfASceneEditedSinceTheListIsRefusedNamingTheProbeAndNothingIsBaked) {
    // A copy of the scene, so it can be edited after the list is written.
    const fs::path copy = root_ / "scene";
    fs::create_directories(copy);
    for (const auto& f : fs::directory_iterator(fs::path(kTwoRooms).parent_path()))
        fs::copy_file(f.path(), copy / f.path().filename());
    const std::string gltf = (copy / fs::path(kTwoRooms).filename()).string();
    {
        ProbeScene scene(gltf, "");
        LevelCookOptions o = options("level", distance());
        o.cook.scene = gltf;
        writeShardList(scene, o, nullptr);
    }
    const std::string dir = (root_ / "level").string();
    std::ifstream in(gltf);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    // room_b's east panel moves 10 cm: within reach of room_b's probe (shard 1).
    const std::string from = " 5.93,", to = " 5.83,";
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << "room_b_panel's translation not found";
    text.replace(at, from.size(), to);
    std::ofstream(gltf) << text;
    try {
        bakeShard(dir, 1, nullptr);
        FAIL() << "baked a shard of an edited scene";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("changed since the shard list was written (the geometry within "
                            "reach of probe room_b_probe, shard 1)"),
                  std::string::npos)
            << what;
    }
    EXPECT_FALSE(shardPresent(dir, readShardList(dir).shards[1]));
}

TEST_F(ShardBake, AMergeWithAShardMissingNamesItAndWritesNothing) {
    ProbeScene scene(kTwoRooms, "");
    writeShardList(scene, options("level", distance()), nullptr);
    const std::string dir = (root_ / "level").string();
    bakeShard(dir, 0, nullptr);
    try {
        mergeShards(dir, nullptr);
        FAIL() << "merged with a shard missing";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("1 of 2 shards not baked: 1 (probe room_b_probe"), std::string::npos)
            << what;
    }
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename(), ".shards") << e.path() << " written by a failed merge";
}

TEST_F(ShardBake, AnIndexOutOfRangeOrAMissingListIsAnErrorNamingIt) {
    const std::string dir = (root_ / "level").string();
    try {
        bakeShard(dir, 0, nullptr);
        FAIL() << "baked a shard without a list";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no shard list"), std::string::npos) << e.what();
    }
    // Through the tool: the list is written, "2 shards" printed; index 2 is out of range.
    std::ostringstream out, err;
    ASSERT_EQ(cook::runCli(
                  std::vector<std::string>{"shards", kTwoRooms, "--out", dir, "--face-res", "16"},
                  out, err),
              0)
        << err.str();
    EXPECT_NE(out.str().find("2 shards"), std::string::npos) << out.str();
    std::ostringstream out2, err2;
    EXPECT_EQ(cook::runCli(std::vector<std::string>{"bake-shard", dir, "--shard", "2"}, out2, err2),
              1);
    EXPECT_NE(err2.str().find("index 2 is out of range: the list has 2 shards"), std::string::npos)
        << err2.str();
}

TEST_F(ShardBake, ShardRowsOutOfRangeAreRefusedAndTheCountIsSixBlocksASlabPlusTheProbe) {
    const std::string dir = (root_ / "level").string();
    auto shards = [&](std::vector<std::string> extra, std::string& text) {
        std::vector<std::string> args = {"shards",      kTwoRooms,    "--out",     dir,
                                         "--flavour",   "lightfield", "--cameras", "3",
                                         "--image-res", "8"};
        args.insert(args.end(), extra.begin(), extra.end());
        std::ostringstream out, err;
        const int rc = cook::runCli(args, out, err);
        text = out.str() + err.str();
        return rc;
    };
    std::string text;
    for (const char* bad : {"0", "4"}) {
        EXPECT_EQ(shards({"--shard-rows", bad}, text), 2) << text;
        EXPECT_NE(
            text.find("--shard-rows: expected 1 .. NUM = --cameras 3, got " + std::string(bad)),
            std::string::npos)
            << text;
    }
    EXPECT_FALSE(fs::exists(shardListPath(dir)));
    // Two probes, each 6 x ceil(3 / rows) parts and its own shard.
    for (const auto& [rows, count] : std::vector<std::pair<std::string, int>>{
             {"1", 2 * (6 * 3 + 1)}, {"2", 2 * (6 * 2 + 1)}, {"3", 2 * (6 + 1)}}) {
        ASSERT_EQ(shards({"--shard-rows", rows}, text), 0) << text;
        EXPECT_NE(text.find(std::to_string(count) + " shards ("), std::string::npos) << text;
        EXPECT_EQ(readShardList(dir).shards.size(), std::size_t(count));
    }
    ASSERT_EQ(shards({}, text), 0) << text;
    EXPECT_NE(text.find("14 shards (12 light-field part shards of 3 camera rows + 2 probe"),
              std::string::npos)
        << text;
    // A distance level has no part shards.
    std::ostringstream out, err;
    EXPECT_EQ(cook::runCli(
                  std::vector<std::string>{"shards", kTwoRooms, "--out", dir, "--shard-rows", "1"},
                  out, err),
              2);
    EXPECT_NE(err.str().find("--shard-rows: applies to --flavour lightfield"), std::string::npos)
        << err.str();
}

// The shard list is read on every farm node from a shared disk (issue 34): a damaged list is
// an Error naming the list, never a crash or a stray exception. A distance and a light-field
// list the cooker writes, and a PEM's (the fuzz corpus's), are each damaged in 300 seeded
// ways, one member at a time (removed, or given a value of another type or range), and read.
TEST_F(ShardBake, EveryDamagedMemberOfAShardListIsAnErrorNamingTheList) {
    ProbeScene scene(kTwoRooms, "");
    std::mt19937 random(34);
    int refused = 0, read = 0;
    const std::string file = shardListPath((root_ / "level").string());
    std::vector<nlohmann::json> lists;
    for (const CookFlavour& flavour : {distance(), lightField()}) {
        writeShardList(scene, options("level", flavour), nullptr, 1);
        lists.push_back(nlohmann::json::parse(std::ifstream(file)));
    }
    // A PEM's list, as `specula-cook shards` wrote it for the room's camera path.
    lists.push_back(nlohmann::json::parse(
        std::ifstream(SPECULA_SOURCE_DIR "/tests/fuzz/corpus/shards/pem.json")));
    for (const nlohmann::json& good : lists) {
        EXPECT_NO_THROW(shardListFromJson(good, file));
        // Every member's JSON pointer, the root's children first.
        std::vector<nlohmann::json::json_pointer> members;
        const nlohmann::json flat = good.flatten();
        for (auto it = flat.begin(); it != flat.end(); ++it) {
            nlohmann::json::json_pointer p(it.key());
            for (; !p.empty(); p = p.parent_pointer())
                members.push_back(p);
        }
        const nlohmann::json others[] = {nullptr,
                                         -1,
                                         0,
                                         1e300,
                                         2147483648.0,
                                         "",
                                         "../x",
                                         "shards",
                                         true,
                                         7,
                                         0.5,
                                         nlohmann::json::array(),
                                         nlohmann::json::object()};
        for (int trial = 0; trial < 300; ++trial) {
            nlohmann::json bad = good;
            const nlohmann::json::json_pointer& p = members[random() % members.size()];
            if (random() % 4 == 0)
                bad[p.parent_pointer()].is_object() ? (void)bad[p.parent_pointer()].erase(p.back())
                                                    : (void)(bad[p] = nullptr);
            else
                bad[p] = others[random() % std::size(others)];
            try {
                shardListFromJson(bad, file);
                ++read;
            } catch (const Error& e) {
                EXPECT_EQ(e.file(), file) << e.what();
                ++refused;
            } catch (const std::exception& e) {
                ADD_FAILURE() << p.to_string() << ": " << e.what() << " escaped the reader";
            }
        }
    }
    std::printf("900 damaged shard lists: %d refused, %d still read\n", refused, read);
    EXPECT_GT(refused, 600);
}

} // namespace
} // namespace specula
