#pragma once
// The fixture of the shard bake tests: the two-room level's options and a sharded-vs-plain check.
#include "assetcooker/lib/farm/shard_bake.h"
#include "support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace specula::test::shard_bake {

inline double secondsSince(std::chrono::steady_clock::time_point start) {
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
        return o;
    }

    static CookFlavour distance(int faceRes = 16) {
        DistanceCookSettings d;
        d.faceRes = faceRes;
        return d;
    }

    static CookFlavour lightField(int cameras = 2) {
        LightFieldCookSettings l;
        l.cameras = cameras;
        l.imageRes = 8;
        return l;
    }

    enum class Order { Reverse, Shuffled };

    // The in-process bake into `plain`, the leaf shards in `order` (then the probe shards
    // too when `probeShards`; else the merge assembles them) and a merge into `sharded`:
    // every file the same. `expectedShards`: the list's length. Prints the timings.
    void expectShardedEqualsPlain(const CookFlavour& flavour, const std::string& label,
                                  std::size_t expectedShards, int shardRows = 0,
                                  Order order = Order::Reverse, bool probeShards = false) {
        ProbeScene scene(kTwoRooms, "");
        auto start = std::chrono::steady_clock::now();
        cookLevel(scene, options("plain", flavour), nullptr);
        const double plainSeconds = secondsSince(start);

        start = std::chrono::steady_clock::now();
        const ShardList list =
            writeShardList(scene, options("sharded", flavour), nullptr, shardRows);
        const double listSeconds = secondsSince(start);
        ASSERT_EQ(list.shards.size(), expectedShards);
        std::set<std::string> hashes;
        for (const Shard& s : list.shards)
            hashes.insert(s.hash);
        EXPECT_EQ(hashes.size(), list.shards.size()) << "two shards share a hash";
        const std::string dir = (root_ / "sharded").string();
        std::vector<int> leaves, probes;
        for (int i = 0; i < int(list.shards.size()); ++i)
            (shardDependencies(list, i).empty() ? leaves : probes).push_back(i);
        std::reverse(leaves.begin(), leaves.end());
        if (order == Order::Shuffled) std::shuffle(leaves.begin(), leaves.end(), std::mt19937(11));
        if (probeShards) leaves.insert(leaves.end(), probes.begin(), probes.end());
        double shardSeconds = 0, shardWall = 0;
        for (const int i : leaves) {
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
        // Installed by hard link (one scratch file system): the merge did not copy the bytes.
        // The manifest and the index are written by the merge itself.
        int linked = 0;
        for (const auto& e : std::filesystem::recursive_directory_iterator(root_ / "sharded")) {
            const std::string name = e.path().filename().string();
            if (!e.is_regular_file() || name == "manifest.json" || name == "level.json" ||
                e.path().string().find("/.shards/") != std::string::npos)
                continue;
            EXPECT_GE(std::filesystem::hard_link_count(e.path()), 2u) << e.path();
            ++linked;
        }
        EXPECT_GT(linked, 0) << "no probe file to check";
    }
};

} // namespace specula::test::shard_bake
