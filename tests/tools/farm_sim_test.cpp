// The farm simulation (farm_sim.h): the list scheduler against closed-form cases, then
// `specula-cook farm` on the two-room level (two probes) reading the times bake-shard
// recorded, and naming the shards that have none.
#include "assetcooker/lib/cli/cli.h"
#include "assetcooker/lib/farm/farm_sim.h"
#include "assetcooker/lib/farm/shard_bake.h"
#include "engine/core/error.h"
#include "support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;

TEST(FarmWall, EqualShardsDivideEvenlyOverTheNodes) {
    const std::vector<double> eight(8, 2.0);
    EXPECT_DOUBLE_EQ(farmWall(eight, 1, 0, 0), 16.0);
    EXPECT_DOUBLE_EQ(farmWall(eight, 2, 0, 0), 8.0);
    EXPECT_DOUBLE_EQ(farmWall(eight, 4, 0, 0), 4.0);
    EXPECT_DOUBLE_EQ(farmWall(eight, 8, 0, 0), 2.0);
    EXPECT_DOUBLE_EQ(farmWall(eight, 64, 0, 0), 2.0); // idle nodes do not help
    EXPECT_DOUBLE_EQ(farmWall(eight, 3, 0, 0), 6.0);  // 3 + 3 + 2 shards
}

TEST(FarmWall, OneLongShardBoundsTheWall) {
    // 10 s and ten 1 s shards: on 2+ nodes the long one alone sets the wall (the rest fit on
    // the other nodes in 10 s); on one node everything adds up.
    std::vector<double> s(10, 1.0);
    s.push_back(10.0);
    EXPECT_DOUBLE_EQ(farmWall(s, 1, 0, 0), 20.0);
    EXPECT_DOUBLE_EQ(farmWall(s, 2, 0, 0), 10.0);
    EXPECT_DOUBLE_EQ(farmWall(s, 16, 0, 0), 10.0);
    // Longest first: the order given does not matter.
    std::vector<double> reversed(s.rbegin(), s.rend());
    EXPECT_DOUBLE_EQ(farmWall(reversed, 2, 0, 0), 10.0);
}

TEST(FarmWall, OverheadIsPaidPerShardOnEachNodesChainAndByTheMerge) {
    const std::vector<double> eight(8, 2.0);
    // 4 nodes, 2 shards each: 2 x (0.5 + 2) on the chain, then the merge job 0.5 + 1.
    EXPECT_DOUBLE_EQ(farmWall(eight, 4, 0.5, 1.0), 2 * 2.5 + 1.5);
    EXPECT_DOUBLE_EQ(farmWall(eight, 1, 0.5, 0.0), 8 * 2.5 + 0.5);
    EXPECT_DOUBLE_EQ(farmWall({}, 4, 0.5, 1.0), 1.5); // no shards: the merge alone
}

TEST(FarmWall, TheDependentsArrayStartsWhenEveryLeafIsDone) {
    // Leaves 4, 1, 1 and dependents 2, 2 on 2 nodes: the leaves end at 4 (4 | 1 + 1), the
    // dependents then take 2 more on both nodes, the merge 0.5 after: 6.5, although a node is
    // idle from 2 to 4 (afterok on the whole first array).
    EXPECT_DOUBLE_EQ(farmWall({4, 1, 1}, 2, 0, 0.5, {2, 2}), 6.5);
    EXPECT_DOUBLE_EQ(arrayWall({4, 1, 1}, 2, 0), 4.0);
    EXPECT_DOUBLE_EQ(arrayWall({2, 2}, 2, 0), 2.0);
    // One node: everything in a chain, each shard paying its overhead, the merge its own.
    EXPECT_DOUBLE_EQ(farmWall({4, 1, 1}, 1, 0.25, 0.5, {2, 2}), 10 + 5 * 0.25 + 0.75);
    // No dependents: no second array, nothing paid for it.
    EXPECT_DOUBLE_EQ(farmWall({4, 1, 1}, 2, 0.25, 0.5, {}), 4.25 + 0.75);
    EXPECT_DOUBLE_EQ(arrayWall({}, 8, 0.25), 0.0);
}

TEST(FarmWall, RowsReportTheIdealAndTheRatio) {
    FarmTimes t;
    for (int i = 0; i < 4; ++i)
        t.shards.push_back({i, "p" + std::to_string(i), 3.0});
    const std::vector<FarmRow> rows = simulateFarm(t, {1, 4, 16}, 0.0);
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_DOUBLE_EQ(rows[0].ideal, 12.0);
    EXPECT_DOUBLE_EQ(rows[0].ratio, 1.0);
    EXPECT_DOUBLE_EQ(rows[1].wall, 3.0);
    EXPECT_DOUBLE_EQ(rows[1].ratio, 1.0);
    EXPECT_DOUBLE_EQ(rows[2].ideal, 0.75); // 4 shards cannot use 16 nodes: 4x the ideal
    EXPECT_DOUBLE_EQ(rows[2].ratio, 4.0);
}

class FarmCli : public test::ScratchDirTest {
protected:
    FarmCli() : ScratchDirTest("specula-farm") {}

    int cook(const std::vector<std::string>& args, std::string* output = nullptr) {
        std::ostringstream out, err;
        const int rc = cook::runCli(args, out, err);
        if (output) *output = out.str() + err.str();
        return rc;
    }
};

TEST_F(FarmCli, FarmReadsTheRecordedShardTimesAndNamesTheMissingOnes) {
    const std::string dir = (root_ / "level").string();
    ASSERT_EQ(cook({"shards", test::kTwoRooms, "--out", dir, "--face-res", "16"}), 0);
    ASSERT_EQ(cook({"bake-shard", dir, "--shard", "0"}), 0);
    std::string out;
    EXPECT_EQ(cook({"farm", dir}, &out), 1);
    EXPECT_NE(out.find("1 of 2 shards have no recorded time: 1 (probe room_b_probe"),
              std::string::npos)
        << out;

    ASSERT_EQ(cook({"bake-shard", dir, "--shard", "1"}), 0);
    ASSERT_EQ(cook({"merge", dir}), 0);
    const FarmTimes times = readFarmTimes(dir);
    ASSERT_EQ(times.shards.size(), 2u);
    EXPECT_TRUE(times.mergeRecorded);
    for (const FarmShardTime& s : times.shards)
        EXPECT_GT(s.seconds, 0.0) << s.label;

    const std::string csv = (root_ / "farm.csv").string(), png = (root_ / "farm.png").string();
    ASSERT_EQ(
        cook({"farm", dir, "--nodes", "1,2,4", "--overhead", "0.5", "--csv", csv, "--plot", png},
             &out),
        0)
        << out;
    EXPECT_NE(out.find("level: 2 shards"), std::string::npos) << out;
    EXPECT_TRUE(fs::is_regular_file(png));
    // The CSV's rows are the simulation of the recorded times: on one node both shards and
    // their overheads in a chain; on 2 and 4 nodes the longer shard alone.
    std::ifstream in(csv);
    std::string header, line;
    std::getline(in, header);
    EXPECT_EQ(header, "level,shards,dependents,total_s,merge_s,nodes,wall_s,ideal_s,ratio");
    const double a = times.shards[0].seconds, b = times.shards[1].seconds;
    const double merge = 0.5 + times.mergeSeconds;
    const double expected[] = {a + b + 1.0 + merge, std::max(a, b) + 0.5 + merge,
                               std::max(a, b) + 0.5 + merge};
    int rows = 0;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');)
            cells.push_back(c);
        ASSERT_EQ(cells.size(), 9u) << line;
        EXPECT_EQ(cells[0], "level");
        EXPECT_EQ(cells[1], "2");
        EXPECT_EQ(cells[2], "0"); // a distance level has no dependent shards
        EXPECT_NEAR(std::stod(cells[6]), expected[rows], 1e-4 * expected[rows]) << line;
        ++rows;
    }
    EXPECT_EQ(rows, 3);
}

TEST_F(FarmCli, ALightFieldLevelsProbesAreTheSecondArrayWhoeverComputedThem) {
    const std::string dir = (root_ / "level").string();
    ASSERT_EQ(cook({"shards", test::kTwoRooms, "--out", dir, "--flavour", "lightfield", "--cameras",
                    "2", "--image-res", "8", "--shard-rows", "1"}),
              0);
    const ShardList list = readShardList(dir);
    ASSERT_EQ(list.shards.size(), 26u); // 2 x (6 slabs x 2 rows + the probe)
    for (int i = 0; i < 26; ++i) {
        if (shardDependencies(list, i).empty()) {
            ASSERT_EQ(cook({"bake-shard", dir, "--shard", std::to_string(i)}), 0);
        }
    }
    // Before the probes are computed the farm names them, and says merge would record them.
    std::string out;
    EXPECT_EQ(cook({"farm", dir}, &out), 1);
    EXPECT_NE(out.find("2 of 26 shards have no recorded time: 12 (probe room_a_probe"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("or merge"), std::string::npos) << out;
    // Probe room_a_probe computed by bake-shard (the second array's way), room_b_probe by the
    // merge.
    ASSERT_EQ(cook({"bake-shard", dir, "--shard", "12"}), 0);
    ASSERT_EQ(cook({"merge", dir}), 0);
    const FarmTimes times = readFarmTimes(dir);
    ASSERT_EQ(times.shards.size(), 24u); // the parts: the first array
    for (const FarmShardTime& s : times.shards) {
        EXPECT_NE(s.label.find(", part "), std::string::npos) << s.label;
        EXPECT_GT(s.seconds, 0.0) << s.label;
    }
    ASSERT_EQ(times.dependents.size(), 2u); // the probes, whoever computed them
    auto seconds = [](const std::string& file, const char* field) {
        std::ifstream in(file);
        return nlohmann::json::parse(in).at(field).get<double>();
    };
    EXPECT_EQ(times.dependents[0].index, 12);
    EXPECT_DOUBLE_EQ(times.dependents[0].seconds,
                     seconds(shardTimePath(dir, list.shards[12]), "seconds"));
    EXPECT_DOUBLE_EQ(times.dependents[1].seconds,
                     seconds(shardTimePath(dir, list.shards[25]), "seconds"));
    // The merge job's own time: merge's less the probe it computed.
    EXPECT_TRUE(times.mergeRecorded);
    const double merged = seconds(mergeTimePath(dir), "seconds");
    const double assembly = seconds(mergeTimePath(dir), "assembly_seconds");
    EXPECT_GE(assembly, times.dependents[1].seconds);
    EXPECT_NEAR(times.mergeSeconds, merged - assembly, 1e-9);
    // On one node with no overhead the wall is every shard's seconds and the merge's.
    const std::vector<FarmRow> rows = simulateFarm(times, {1}, 0.0);
    EXPECT_NEAR(rows[0].wall, times.total() + times.mergeSeconds, 1e-9);
    ASSERT_EQ(cook({"farm", dir, "--nodes", "1,64"}, &out), 0) << out;
    EXPECT_NE(out.find("level: 24 shards + 2 dependent shards"), std::string::npos) << out;
}

TEST_F(FarmCli, AMergeTimeFromBeforeTheAssemblyFieldSubtractsTheProbesItComputed) {
    const std::string dir = (root_ / "level").string();
    ASSERT_EQ(cook({"shards", test::kTwoRooms, "--out", dir, "--flavour", "lightfield", "--cameras",
                    "2", "--image-res", "8", "--shard-rows", "2"}),
              0);
    const ShardList list = readShardList(dir);
    for (int i = 0; i < int(list.shards.size()); ++i) {
        if (shardDependencies(list, i).empty()) {
            ASSERT_EQ(cook({"bake-shard", dir, "--shard", std::to_string(i)}), 0);
        }
    }
    ASSERT_EQ(cook({"merge", dir}), 0);
    // Rewritten as a session-24 merge wrote it: no assembly_seconds.
    std::ifstream in(mergeTimePath(dir));
    nlohmann::json doc = nlohmann::json::parse(in);
    in.close();
    doc.erase("assembly_seconds");
    doc["seconds"] = 100.0;
    std::ofstream(mergeTimePath(dir)) << doc.dump();
    const FarmTimes times = readFarmTimes(dir);
    double byMerge = 0;
    for (const FarmShardTime& s : times.dependents)
        byMerge += s.seconds;
    EXPECT_NEAR(times.mergeSeconds, 100.0 - byMerge, 1e-9);
    // A malformed field is named.
    doc["assembly_seconds"] = -1;
    std::ofstream(mergeTimePath(dir)) << doc.dump();
    try {
        readFarmTimes(dir);
        ADD_FAILURE() << "a negative assembly_seconds was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("assembly_seconds"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace specula
