// `bake --slurm` through a real one-node Slurm (scripts/local-slurm, started here when it is
// not running and stopped after; skipped unless root with slurm-wlm and munge installed, as in
// CI after scripts/install-deps). The two-room level (two probes), 16^2 faces or a 2^2 x 8^2
// light field: the sharded bake equals the in-process bake byte for byte (both flavours, the
// light-field probe shards in a second array after their parts), and so does a PEM of the
// bowl room (its trace shards, then its sample shards as a second array, then the merge); a
// shard cancelled with scancel is reported, and the resume submits that shard alone and gives
// the same files; a shard that fails every time is reported by index and nothing is merged.
// Prints the per-shard scheduling overhead (not asserted).
#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/slurm_bake.h"
#include "support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <iostream>
#include <sys/file.h>
#include <unistd.h>

namespace specula {
namespace {

namespace fs = std::filesystem;

const std::string kLocalSlurm = std::string(SPECULA_SOURCE_DIR) + "/scripts/local-slurm";

// The real scheduler, which cancels task `cancelTask` of the first array right after its
// submission.
class CancellingRunner : public SystemProcessRunner {
public:
    int cancelTask = -1;
    ProcessResult run(const std::vector<std::string>& argv) override {
        ProcessResult r = SystemProcessRunner::run(argv);
        const auto isArray = [](const std::string& a) { return a.rfind("--array=", 0) == 0; };
        if (cancelTask >= 0 && argv[0] == "sbatch" &&
            std::any_of(argv.begin(), argv.end(), isArray)) {
            const std::string id = r.output.substr(0, r.output.find_first_of(";\n"));
            SystemProcessRunner::run({"scancel", id + "_" + std::to_string(cancelTask)});
            cancelTask = -1;
        }
        return r;
    }
};

class SlurmCluster : public test::ScratchDirTest {
protected:
    SlurmCluster() : ScratchDirTest("specula-slurm") {}

    static void SetUpTestSuite() {
        if (::geteuid() != 0) {
            skip_ = "needs root to start the local Slurm (scripts/local-slurm)";
            return;
        }
        if (std::system("command -v sbatch >/dev/null && command -v slurmctld >/dev/null && "
                        "command -v munged >/dev/null") != 0) {
            skip_ = "slurm-wlm or munge not installed (scripts/install-deps)";
            return;
        }
        // ctest runs tests in parallel, one process each: one process at a time owns the
        // cluster (it may start and stop it), the others wait here.
        lockFd_ = ::open("/tmp/specula-slurm-test.lock", O_CREAT | O_RDWR, 0644);
        if (lockFd_ < 0 || ::flock(lockFd_, LOCK_EX) != 0) {
            skip_ = "cannot lock /tmp/specula-slurm-test.lock";
            return;
        }
        const char* dir = std::getenv("SPECULA_SLURM_DIR");
        ::setenv("SLURM_CONF",
                 ((dir ? std::string(dir) : "/tmp/specula-slurm") + "/slurm.conf").c_str(), 1);
        started_ = std::system((kLocalSlurm + " status >/dev/null").c_str()) != 0;
        if (started_ && std::system((kLocalSlurm + " start").c_str()) != 0)
            skip_ = "scripts/local-slurm start failed";
    }
    static void TearDownTestSuite() {
        if (started_) std::system((kLocalSlurm + " stop").c_str());
        if (lockFd_ >= 0) ::close(lockFd_); // releases the lock
    }
    void SetUp() override {
        if (!skip_.empty()) GTEST_SKIP() << skip_;
        ScratchDirTest::SetUp();
    }

    LevelCookOptions options(const std::string& out, CookFlavour flavour) const {
        LevelCookOptions o;
        o.cook.scene = test::kTwoRooms;
        o.cook.out = (root_ / out).string();
        o.cook.flavour = std::move(flavour);
        o.cook.progress = false;
        return o;
    }
    static CookFlavour distance() {
        DistanceCookSettings d;
        d.faceRes = 16;
        return d;
    }
    static SlurmOptions slurm(int retries) {
        SlurmOptions o;
        o.cook = std::string(SPECULA_BIN_DIR) + "/specula-cook";
        o.retries = retries;
        o.pollSeconds = 0.1;
        o.progress = false;
        return o;
    }
    // The in-process bake of `flavour` into "plain" and the shard list into "sharded".
    std::string plainAndList(const CookFlavour& flavour) {
        ProbeScene scene(test::kTwoRooms, "");
        cookLevel(scene, options("plain", flavour), nullptr);
        writeShardList(scene, options("sharded", flavour), nullptr);
        return (root_ / "sharded").string();
    }
    void expectSameFiles() {
        const auto plain = test::treeBytes(root_ / "plain");
        const auto sharded = test::treeBytes(root_ / "sharded");
        ASSERT_EQ(plain.size(), sharded.size());
        for (const auto& [path, bytes] : plain)
            EXPECT_TRUE(sharded.count(path) && sharded.at(path) == bytes) << path << " differs";
    }

    static inline std::string skip_;
    static inline bool started_ = false;
    static inline int lockFd_ = -1;
};

TEST_F(SlurmCluster, BothFlavoursBakeOnTheClusterToThePlainBakeByteForByte) {
    LightFieldCookSettings l;
    l.cameras = 2;
    l.imageRes = 8;
    for (const CookFlavour& flavour : {distance(), CookFlavour(l)}) {
        fs::remove_all(root_ / "plain");
        fs::remove_all(root_ / "sharded");
        const std::string dir = plainAndList(flavour);
        SystemProcessRunner runner;
        const SlurmBakeResult r = bakeOnSlurm(dir, slurm(0), runner, nullptr);
        ASSERT_TRUE(r.merged) << slurmFailureReport(r);
        // Distance: a shard a probe; light field: each probe's 6 parts (one a slab) in the
        // array, its own shard in the second array.
        const std::vector<int> leaves =
            flavour.index() == 0 ? std::vector<int>{0, 1}
                                 : std::vector<int>{0, 1, 2, 3, 4, 5, 7, 8, 9, 10, 11, 12};
        EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{leaves}));
        const std::vector<std::vector<int>> dependents =
            flavour.index() == 0 ? std::vector<std::vector<int>>{}
                                 : std::vector<std::vector<int>>{{6, 13}};
        EXPECT_EQ(r.dependentArrays, dependents);
        EXPECT_EQ(r.shardsBaked, int(leaves.size() + (flavour.index() == 0 ? 0 : 2)));
        std::cout << (flavour.index() == 0 ? "distance" : "light field") << ": " << r.shardsBaked
                  << " shards on slurm (" << leaves.size() << " leaves) " << r.shardWallSeconds
                  << " s from submission to the last shard's end, their "
                  << "bakes " << r.shardComputeSeconds << " s: overhead "
                  << (r.shardWallSeconds - r.shardComputeSeconds) / double(r.shardsBaked)
                  << " s per shard; with the merge job " << r.seconds << " s\n";
        expectSameFiles();
    }
}

TEST_F(SlurmCluster, APemBakesOnTheClusterToThePlainBakeByteForByte) {
    const std::string bowl = std::string(SPECULA_SOURCE_DIR) + "/assets/bowl_room/bowl_room.gltf";
    PemCookSettings p;
    p.samples = 3;
    p.faceRes = 12;
    p.imageWidth = 64, p.imageHeight = 48;
    ProbeScene scene(bowl, "");
    LevelCookOptions o = options("plain/pem", p);
    o.cook.scene = bowl;
    cookProbe(scene, o.cook, nullptr);
    o.cook.out = (root_ / "sharded").string();
    writeShardList(scene, o, nullptr);
    SystemProcessRunner runner;
    const SlurmBakeResult r = bakeOnSlurm(o.cook.out, slurm(0), runner, nullptr);
    ASSERT_TRUE(r.merged) << slurmFailureReport(r);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1, 2}}));
    EXPECT_EQ(r.dependentArrays, (std::vector<std::vector<int>>{{3, 4, 5}}));
    EXPECT_EQ(r.shardsBaked, 6);
    std::cout << "pem: 6 shards on slurm " << r.shardWallSeconds << " s to the last shard's end, "
              << "their bakes " << r.shardComputeSeconds << " s; with the merge job " << r.seconds
              << " s\n";
    expectSameFiles();
}

TEST_F(SlurmCluster, ACancelledShardAloneRerunsOnResumeAndTheResultIsTheSame) {
    const std::string dir = plainAndList(distance());
    CancellingRunner cancelling;
    cancelling.cancelTask = 1;
    SlurmOptions o = slurm(0);
    o.maxParallel = 1; // shard 1 waits behind shard 0: it is cancelled before it is baked
    const SlurmBakeResult first = bakeOnSlurm(dir, o, cancelling, nullptr);
    EXPECT_FALSE(first.merged);
    ASSERT_EQ(first.failures.size(), 1u) << slurmFailureReport(first);
    EXPECT_EQ(first.failures[0].index, 1);
    EXPECT_EQ(first.failures[0].state, "CANCELLED");
    EXPECT_FALSE(fs::exists(fs::path(dir) / "level.json"));

    SystemProcessRunner runner;
    const SlurmBakeResult resumed = bakeOnSlurm(dir, slurm(0), runner, nullptr);
    ASSERT_TRUE(resumed.merged) << slurmFailureReport(resumed);
    EXPECT_EQ(resumed.arrays, (std::vector<std::vector<int>>{{1}}));
    expectSameFiles();
}

TEST_F(SlurmCluster, AShardThatFailsEveryTimeIsReportedByIndexAndNothingMerges) {
    const std::string dir = plainAndList(distance());
    // Shard 1's place in the store is taken by a file: its bake cannot write there.
    const ShardList list = readShardList(dir);
    std::ofstream(fs::path(shardStore(dir)) / list.shards[1].hash) << "in the way\n";
    SystemProcessRunner runner;
    const SlurmBakeResult r = bakeOnSlurm(dir, slurm(1), runner, nullptr);
    EXPECT_FALSE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1}, {1}}));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].index, 1);
    EXPECT_EQ(r.failures[0].probe, "room_b_probe");
    EXPECT_EQ(r.failures[0].state, "FAILED");
    EXPECT_FALSE(r.failures[0].logTail.empty());
    std::cout << slurmFailureReport(r);
    EXPECT_FALSE(fs::exists(fs::path(dir) / "level.json"));
    EXPECT_FALSE(fs::exists(fs::path(dir) / "room_a_probe"));
}

} // namespace
} // namespace specula
