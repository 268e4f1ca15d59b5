// One writer per output (issue 34): bake, shards and merge hold DIR.lock exclusively for their
// whole run, bake-shard shared; a second writer fails at once (exit 1) naming the holder's
// command, host and pid, and succeeds once the lock is let go; the last holder removes the lock
// file. Two level bakes into one folder at once: the second fails at once, the first is left
// to finish. The jobs of a `bake --slurm` run under its lock only when they name it.
#include "assetcooker/lib/os/output_lock.h"
#include "engine/core/error.h"
#include "engine/core/host_name.h"
#include "tests/support/child_process.h"
#include "tests/support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <optional>

namespace specula {
namespace {

namespace fs = std::filesystem;
using test::Child;
using test::ChildResult;

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class OutputLockTest : public test::ScratchDirTest {
protected:
    OutputLockTest() : ScratchDirTest("specula-output-lock") {}

    ChildResult cook(const std::vector<std::string>& args, const test::ChildOptions& o = {}) {
        const auto start = std::chrono::steady_clock::now();
        const ChildResult r = test::runChild(kCook, args, root_ / "scratch", o);
        lastSeconds_ = secondsSince(start);
        std::printf("[output-lock] %s: exit %d in %.3f s, stderr: %s", args[0].c_str(), r.status,
                    lastSeconds_, r.err.empty() ? "(empty)\n" : r.err.c_str());
        return r;
    }
    ChildResult bakeLevel() {
        return cook({"bake", test::kTwoRooms, "--out", level().string(), "--face-res", "8"});
    }
    fs::path level() const { return root_ / "level"; }
    std::string holderText(const std::string& command, long long pid) const {
        return command + " (host " + hostName() + ", pid " + std::to_string(pid) + ")";
    }
    double lastSeconds_ = 0;
};

TEST_F(OutputLockTest, ASecondWriterFailsAtOnceNamingTheHolderAndSucceedsOnceItIsFree) {
    ASSERT_EQ(
        cook({"shards", test::kTwoRooms, "--out", level().string(), "--face-res", "8"}).status, 0);
    {
        const OutputLock held(level().string(), "test-writer", FileLockMode::Exclusive);
        EXPECT_EQ(held.path(), level().string() + ".lock");
        const std::string holder = holderText("test-writer", ::getpid());
        for (const std::vector<std::string>& args :
             {std::vector<std::string>{"bake", test::kTwoRooms, "--out", level().string(),
                                       "--face-res", "8"},
              {"merge", level().string()},
              {"bake-shard", level().string(), "--shard", "0"},
              {"shards", test::kTwoRooms, "--out", level().string(), "--face-res", "8"}}) {
            const ChildResult r = cook(args);
            EXPECT_EQ(r.status, 1) << args[0];
            EXPECT_NE(r.err.find(holder), std::string::npos) << r.err;
            EXPECT_NE(r.err.find(held.path()), std::string::npos) << r.err;
            EXPECT_LT(lastSeconds_, 5.0) << args[0] << " must fail at once, not wait";
        }
        EXPECT_FALSE(fs::exists(level() / "level.json"));
        EXPECT_FALSE(fs::exists(level() / "room_a_probe"));
    }
    EXPECT_FALSE(fs::exists(level().string() + ".lock")) << "the last holder removes it";
    const ChildResult r = bakeLevel();
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(level() / "level.json"));
    EXPECT_FALSE(fs::exists(level().string() + ".lock"));
}

TEST_F(OutputLockTest, TwoLevelBakesIntoOneFolderAtOnceTheSecondFailsAtOnce) {
    // The first bake holds its finished first probe before the commit (the test hook) while
    // the second starts: today's mix of the two levels' probes and checksums.
    Child first(kCook, {"bake", test::kTwoRooms, "--out", level().string(), "--face-res", "8"},
                root_ / "scratch", {{"SPECULA_TEST_PAUSE_BEFORE_COMMIT=60"}});
    const std::string staged = ".tmp-" + std::to_string(first.pid());
    ASSERT_TRUE(first.waitFor(
        [&] {
            std::error_code ec;
            for (const auto& e : fs::directory_iterator(level(), ec))
                if (e.path().filename().string().ends_with(staged) &&
                    fs::exists(e.path() / "manifest.json"))
                    return true;
            return false;
        },
        120))
        << "the first bake never staged a probe";
    fs::create_directories(root_ / "second");
    const auto start = std::chrono::steady_clock::now();
    const ChildResult second = test::runChild(
        kCook, {"bake", test::kTwoRooms, "--out", level().string(), "--face-res", "8"},
        root_ / "second");
    const double seconds = secondsSince(start);
    std::printf("[output-lock] the second bake: exit %d in %.3f s: %s", second.status, seconds,
                second.err.c_str());
    EXPECT_EQ(second.status, 1);
    EXPECT_NE(second.err.find(holderText("bake", first.pid())), std::string::npos) << second.err;
    EXPECT_LT(seconds, 5.0);
    first.signal(SIGTERM);
    EXPECT_EQ(first.wait().status, 130);
    EXPECT_FALSE(fs::exists(level().string() + ".lock"));
    const ChildResult again = bakeLevel();
    EXPECT_EQ(again.status, 0) << again.err;
}

TEST_F(OutputLockTest, BakeShardsShareTheLockAndAMergeNamesThem) {
    ASSERT_EQ(
        cook({"shards", test::kTwoRooms, "--out", level().string(), "--face-res", "8"}).status, 0);
    {
        const OutputLock other(level().string(), "bake-shard", FileLockMode::Shared);
        const ChildResult shard = cook({"bake-shard", level().string(), "--shard", "0"});
        EXPECT_EQ(shard.status, 0) << shard.err;
        const ChildResult merge = cook({"merge", level().string()});
        EXPECT_EQ(merge.status, 1);
        EXPECT_NE(merge.err.find(holderText("bake-shard", ::getpid())), std::string::npos)
            << merge.err;
        EXPECT_FALSE(fs::exists(level() / "level.json"));
        EXPECT_TRUE(fs::exists(level().string() + ".lock")) << "still held by the test";
    }
    EXPECT_EQ(cook({"bake-shard", level().string(), "--shard", "1"}).status, 0);
    const ChildResult merge = cook({"merge", level().string()});
    EXPECT_EQ(merge.status, 0) << merge.err;
    EXPECT_TRUE(fs::exists(level() / "level.json"));
}

TEST_F(OutputLockTest, JobsRunUnderTheirSubmittersLockOnlyWhenTheyNameIt) {
    ASSERT_EQ(
        cook({"shards", test::kTwoRooms, "--out", level().string(), "--face-res", "8"}).status, 0);
    const OutputLock submitter(level().string(), "bake --slurm", FileLockMode::Exclusive);
    const ChildResult stranger =
        cook({"bake-shard", level().string(), "--shard", "0"},
             {{std::string(kLockHolderVariable) + "=host " + hostName() + " pid 1"}});
    EXPECT_EQ(stranger.status, 1);
    EXPECT_NE(stranger.err.find(holderText("bake --slurm", ::getpid())), std::string::npos);
    const ChildResult job = cook({"bake-shard", level().string(), "--shard", "0"},
                                 {{std::string(kLockHolderVariable) + "=" + submitter.holder()}});
    EXPECT_EQ(job.status, 0) << job.err;
    EXPECT_TRUE(fs::exists(submitter.path())) << "a job never removes its submitter's lock";
}

TEST_F(OutputLockTest, TheLockIsTakenInProcessTooAndFreedWithItsHolder) {
    std::optional<OutputLock> first(std::in_place, (root_ / "out/").string(), "one",
                                    FileLockMode::Exclusive);
    EXPECT_EQ(first->path(), (root_ / "out").string() + ".lock");
    try {
        const OutputLock second((root_ / "out").string(), "two", FileLockMode::Shared);
        ADD_FAILURE() << "a second lock was granted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(holderText("one", ::getpid())), std::string::npos)
            << e.what();
    }
    first.reset();
    const OutputLock second((root_ / "out").string(), "two", FileLockMode::Shared);
    // Missing parents are made for the lock file and removed with it when still empty.
    {
        const OutputLock nested((root_ / "made/by/lock").string(), "three",
                                FileLockMode::Exclusive);
        EXPECT_TRUE(fs::exists(root_ / "made/by/lock.lock"));
    }
    EXPECT_FALSE(fs::exists(root_ / "made"));
}

} // namespace
} // namespace specula
