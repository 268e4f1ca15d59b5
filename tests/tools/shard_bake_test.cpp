// A level's bake as shards (shard_bake.h) on the bundled two-room scene (two probes): the
// shards baked in reverse (or shuffled) order and merged give the same files, byte for byte,
// as the in-process bake, for the distance and the light-field flavour, whatever the
// light field's rows a part shard; a shard already in the store is skipped. Also prints the
// shards' overhead (not asserted). What is refused, and named: shard_bake_refusals_test.cpp.
#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/shard_checksum.h"
#include "shard_bake_fixture.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <string>

namespace specula {
namespace {

namespace fs = std::filesystem;

using test::kTwoRooms;
using test::shard_bake::ShardBake;

TEST_F(ShardBake, DistanceShardsInReverseOrderMergeToThePlainBakeByteForByte) {
    expectShardedEqualsPlain(distance(), "distance, 16^2 faces", 2);
}

TEST_F(ShardBake, LightFieldShardsInReverseOrderMergeToThePlainBakeByteForByte) {
    // One part a slab (6) and the probe's shard, for each of the two probes; the probe
    // shards baked by bake-shard after their parts.
    expectShardedEqualsPlain(lightField(), "light field, 2^2 cameras x 8^2 px", 2 * (6 + 1), 0,
                             Order::Reverse, true);
}

TEST_F(ShardBake, LightFieldPartsOfOneRowInReverseMergeToThePlainBakeByteForByte) {
    expectShardedEqualsPlain(lightField(3), "light field, 3^2 cameras, 1 row a part",
                             2 * (6 * 3 + 1), 1, Order::Reverse);
}

TEST_F(ShardBake, LightFieldPartsOfTwoRowsShuffledMergeToThePlainBakeByteForByte) {
    // 3 rows in blocks of 2: rows 0 .. 1 and 2 .. 2 of each slab.
    expectShardedEqualsPlain(lightField(3), "light field, 3^2 cameras, 2 rows a part",
                             2 * (6 * 2 + 1), 2, Order::Shuffled);
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
    // Nothing but the list, the one shard, its checksums and its recorded time in the store:
    // no temporaries left beside it.
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(shardStore(dir)))
        ++entries;
    EXPECT_EQ(entries, 4u);
    EXPECT_TRUE(fs::is_regular_file(shardSumPath(dir, readShardList(dir).shards[1])));
    EXPECT_TRUE(fs::is_regular_file(shardTimePath(dir, readShardList(dir).shards[1])));
}

} // namespace
} // namespace specula
