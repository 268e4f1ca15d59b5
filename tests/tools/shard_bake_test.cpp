// A level's bake as shards (shard_bake.h) on the bundled two-room scene (two probes): the
// shards baked in reverse order and merged give the same files, byte for byte, as the
// in-process bake, for the distance and the light-field flavour; a shard already in the
// store is skipped; a merge with a shard missing names it and writes nothing; an index out of
// range names the count. Also prints the shards' overhead (not asserted).
#include "assetcooker/lib/cli.h"
#include "assetcooker/lib/shard_bake.h"
#include "engine/core/error.h"
#include "support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;

using test::kTwoRooms;
using test::treeBytes;

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class ShardBake : public test::ScratchDirTest {
protected:
    ShardBake() : ScratchDirTest("specula-shards") {}

    LevelCookOptions options(const std::string& out, CookFlavour flavour) const {
        LevelCookOptions o;
        o.cook.scene = kTwoRooms;
        o.cook.out = (root_ / out).string();
        o.cook.flavour = std::move(flavour);
        o.cook.progress = false;
        o.optionsText = "test";
        return o;
    }

    static CookFlavour distance(int faceRes = 16) {
        DistanceCookSettings d;
        d.faceRes = faceRes;
        return d;
    }

    static CookFlavour lightField() {
        LightFieldCookSettings l;
        l.cameras = 2;
        l.imageRes = 8;
        return l;
    }

    // The in-process bake into `plain`, the shards in reverse order and a merge into
    // `sharded`: every file the same. Prints the timings.
    void expectShardedEqualsPlain(const CookFlavour& flavour, const std::string& label) {
        ProbeScene scene(kTwoRooms, "");
        auto start = std::chrono::steady_clock::now();
        cookLevel(scene, options("plain", flavour), nullptr);
        const double plainSeconds = secondsSince(start);

        start = std::chrono::steady_clock::now();
        const ShardList list = writeShardList(scene, options("sharded", flavour), nullptr);
        const double listSeconds = secondsSince(start);
        ASSERT_EQ(list.shards.size(), 2u);
        EXPECT_NE(list.shards[0].hash, list.shards[1].hash);
        const std::string dir = (root_ / "sharded").string();
        double shardSeconds = 0, shardWall = 0;
        for (int i = int(list.shards.size()) - 1; i >= 0; --i) {
            start = std::chrono::steady_clock::now();
            const ShardOutcome r = bakeShard(dir, i, nullptr);
            shardWall += secondsSince(start);
            EXPECT_FALSE(r.skipped);
            shardSeconds += r.seconds;
        }
        start = std::chrono::steady_clock::now();
        mergeShards(dir, nullptr);
        const double mergeSeconds = secondsSince(start);
        std::cout << label << ": in-process bake " << plainSeconds << " s; shards: list "
                  << listSeconds << " s + " << list.shards.size() << " shards " << shardWall
                  << " s (bake " << shardSeconds << " s) + merge " << mergeSeconds << " s\n";

        const auto plain = treeBytes(root_ / "plain");
        const auto sharded = treeBytes(root_ / "sharded");
        ASSERT_EQ(plain.size(), sharded.size());
        EXPECT_TRUE(plain.count("level.json"));
        for (const auto& [path, bytes] : plain) {
            ASSERT_TRUE(sharded.count(path)) << path;
            EXPECT_TRUE(sharded.at(path) == bytes) << path << " differs";
        }
    }
};

TEST_F(ShardBake, DistanceShardsInReverseOrderMergeToThePlainBakeByteForByte) {
    expectShardedEqualsPlain(distance(), "distance, 16^2 faces");
}

TEST_F(ShardBake, LightFieldShardsInReverseOrderMergeToThePlainBakeByteForByte) {
    expectShardedEqualsPlain(lightField(), "light field, 2^2 cameras x 8^2 px");
}

TEST_F(ShardBake, ABakedShardIsSkippedTheSecondTime) {
    ProbeScene scene(kTwoRooms, "");
    writeShardList(scene, options("level", distance()), nullptr);
    const std::string dir = (root_ / "level").string();
    const ShardOutcome first = bakeShard(dir, 1, nullptr);
    EXPECT_FALSE(first.skipped);
    const fs::path manifest = fs::path(first.folder) / "manifest.json";
    ASSERT_TRUE(fs::exists(manifest));
    const auto stamp = fs::last_write_time(manifest);
    const ShardOutcome again = bakeShard(dir, 1, nullptr);
    EXPECT_TRUE(again.skipped);
    EXPECT_EQ(again.folder, first.folder);
    EXPECT_EQ(fs::last_write_time(manifest), stamp);
    // Nothing but the list, the one shard and its recorded time in the store: no temporaries
    // left beside it.
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(shardStore(dir)))
        ++entries;
    EXPECT_EQ(entries, 3u);
    EXPECT_TRUE(fs::is_regular_file(shardTimePath(dir, readShardList(dir).shards[1])));
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

} // namespace
} // namespace specula
