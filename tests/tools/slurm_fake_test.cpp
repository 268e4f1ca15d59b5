// bakeOnSlurm's bookkeeping against a stand-in scheduler (no Slurm needed): the fake answers
// sbatch, squeue and scancel, "runs" a task by putting a manifest in the store, and fails the
// shards it is told to. Checked: only the shards the store lacks are submitted; a failed shard
// is resubmitted up to --retries times, alone; one that fails every time is reported by index,
// probe, state and log, and the merge job is cancelled each time, never left to run. A
// light-field level: only its part shards (the leaves) go in the array, the probe shards are
// the merge's; a failing part is reported by index, probe and part. The dependent shards
// (light-field probes, PEM samples) go in a second array after the first succeeded
// (--dependency=afterok), the merge after that; a job whose dependency failed never runs.
// A signal to the submitter (issue 34) cancels every job it submitted, the merge with them,
// waits for them and writes nothing: in-process, and `bake --slurm` against fake sbatch,
// squeue and scancel scripts in PATH (exit 130, scancel given the job ids).
#include "assetcooker/lib/farm/shard_bake.h"
#include "assetcooker/lib/farm/slurm_bake.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "support/child_process.h"
#include "support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace specula {
namespace {

namespace fs = std::filesystem;

const std::string kBowlRoom = SPECULA_SOURCE_DIR "/assets/bowl_room/bowl_room.gltf";

class FakeSlurm : public ProcessRunner {
public:
    explicit FakeSlurm(std::string dir) : dir_(std::move(dir)) {}

    std::map<int, int> failuresLeft; // shard -> how many more times it fails
    std::vector<std::string> cancelled;
    std::vector<std::vector<std::string>> scancels; // each scancel's job ids
    int pauses = 0;
    bool hold = false;      // tasks run until cancelled
    int cancelAtPause = -1; // a signal (requestCancel) arrives during this pause

    ProcessResult run(const std::vector<std::string>& argv) override {
        if (argv[0] == "sbatch") return sbatch(argv);
        if (argv[0] == "scancel") {
            scancels.emplace_back(argv.begin() + 1, argv.end());
            for (std::size_t k = 1; k < argv.size(); ++k) {
                cancelled.push_back(argv[k]);
                for (auto& [id, state] : jobs_)
                    if (id.rfind(argv[k] + "_", 0) == 0 &&
                        (state == "PENDING" || state == "RUNNING"))
                        state = "CANCELLED";
                jobs_[argv[k]] = "CANCELLED";
            }
            return {};
        }
        EXPECT_EQ(argv[0], "squeue");
        std::string out;
        for (const auto& [id, state] : jobs_)
            out += id + "|" + state + "\n";
        // Each look moves every pending job whose dependency succeeded to its end (a job's
        // dependency has a smaller id: it moved first), or a task to RUNNING when held.
        for (auto& [id, state] : jobs_)
            if (state == "PENDING" && dependencyMet(id))
                state = hold && id.find('_') != std::string::npos ? "RUNNING" : finish(id);
        return {0, out};
    }
    void pause(double) override {
        if (++pauses == cancelAtPause) requestCancel();
        if (pauses > 1000) throw std::runtime_error("the bake never stopped polling");
    }

    std::map<std::string, std::vector<std::string>> submitted; // job id -> its argv

private:
    // Slurm's afterok: every task of the job it waits for COMPLETED. One that failed leaves
    // it pending for ever (DependencyNeverSatisfied) until cancelled.
    bool dependencyMet(const std::string& id) const {
        const std::string job = id.substr(0, id.find('_'));
        const auto it = after_.find(job);
        if (it == after_.end()) return true;
        for (const auto& [other, state] : jobs_)
            if ((other == it->second || other.rfind(it->second + "_", 0) == 0) &&
                state != "COMPLETED")
                return false;
        return true;
    }

    ProcessResult sbatch(const std::vector<std::string>& argv) {
        const std::string id = std::to_string(next_++);
        submitted[id] = argv;
        bool merge = false;
        for (const std::string& a : argv) {
            if (a.rfind("--dependency=afterok:", 0) == 0) after_[id] = a.substr(21);
            if (a.rfind("--array=", 0) == 0) {
                std::istringstream list(a.substr(8));
                for (std::string i; std::getline(list, i, ',');)
                    jobs_[id + "_" + i] = "PENDING";
            }
            merge |= a.ends_with("merge.sh");
        }
        if (merge) jobs_[id] = "PENDING";
        return {0, id + "\n"};
    }

    std::string finish(const std::string& id) {
        const std::size_t bar = id.find('_');
        if (bar == std::string::npos) return "COMPLETED"; // the merge: only run when all passed
        const int shard = std::stoi(id.substr(bar + 1));
        if (failuresLeft[shard] > 0) {
            --failuresLeft[shard];
            std::ofstream(fs::path(dir_) / ".shards/slurm/logs" /
                          ("shard-" + std::to_string(shard) + "-job" + id.substr(0, bar) + ".log"))
                << "loading\nerror: the disk is full\n";
            return "FAILED";
        }
        const Shard s = readShardList(dir_).shards[std::size_t(shard)];
        if (s.kind != kProbeShard) { // a part's, a PEM trace's or a PEM sample's file
            std::ofstream(shardOutputPath(dir_, s)) << "shard";
            return "COMPLETED";
        }
        const fs::path folder = shardOutputPath(dir_, s);
        fs::create_directories(folder);
        std::ofstream(folder / "manifest.json") << "{}";
        return "COMPLETED";
    }

    std::string dir_;
    int next_ = 100;
    std::map<std::string, std::string> jobs_;
    std::map<std::string, std::string> after_; // job id -> the job it waits for
};

class SlurmFake : public test::ScratchDirTest {
protected:
    SlurmFake() : ScratchDirTest("specula-slurm-fake") {}
    void SetUp() override {
        ScratchDirTest::SetUp();
        dir_ = (root_ / "level").string();
        DistanceCookSettings d;
        d.faceRes = 16;
        writeList(d, 0);
    }
    void writeList(const CookFlavour& flavour, int shardRows,
                   const std::string& scenePath = test::kTwoRooms) {
        LevelCookOptions o;
        o.cook.scene = scenePath;
        o.cook.out = dir_;
        o.cook.flavour = flavour;
        o.cook.progress = false;
        ProbeScene scene(scenePath, "");
        writeShardList(scene, o, nullptr, shardRows);
    }
    SlurmOptions options(int retries) const {
        SlurmOptions o;
        o.cook = "/opt/specula-cook";
        o.retries = retries;
        o.progress = false;
        return o;
    }
    std::string dir_;
};

TEST_F(SlurmFake, AllShardsPassThenTheMergeRuns) {
    FakeSlurm slurm(dir_);
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(2), slurm, nullptr);
    EXPECT_TRUE(r.merged);
    EXPECT_EQ(r.mergeState, "COMPLETED");
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1}}));
    EXPECT_TRUE(r.failures.empty());
    EXPECT_TRUE(slurm.cancelled.empty());
    std::ifstream script(fs::path(dir_) / ".shards/slurm/shard.sh");
    std::stringstream text;
    text << script.rdbuf();
    EXPECT_NE(text.str().find("'/opt/specula-cook' bake-shard '" + dir_ +
                              "' --shard \"$SLURM_ARRAY_TASK_ID\""),
              std::string::npos)
        << text.str();
}

TEST_F(SlurmFake, AFlakyShardIsResubmittedAloneAndTheLevelMerges) {
    FakeSlurm slurm(dir_);
    slurm.failuresLeft[1] = 1;
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(2), slurm, nullptr);
    EXPECT_TRUE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1}, {1}}));
    EXPECT_EQ(slurm.cancelled, (std::vector<std::string>{"101"})); // the first merge job
}

TEST_F(SlurmFake, AShardThatAlwaysFailsIsReportedAndNothingMerges) {
    FakeSlurm slurm(dir_);
    slurm.failuresLeft[0] = 100;
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(2), slurm, nullptr);
    EXPECT_FALSE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1}, {0}, {0}}));
    // Every merge job was cancelled: none ever ran.
    EXPECT_EQ(slurm.cancelled, (std::vector<std::string>{"101", "103", "105"}));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].index, 0);
    EXPECT_EQ(r.failures[0].probe, "room_a_probe");
    EXPECT_EQ(r.failures[0].state, "FAILED");
    EXPECT_TRUE(r.failures[0].log.ends_with("shard-0-job104.log")) << r.failures[0].log;
    EXPECT_NE(r.failures[0].logTail.find("the disk is full"), std::string::npos);
    const std::string report = slurmFailureReport(r);
    EXPECT_NE(report.find("shard 0 (probe room_a_probe): FAILED"), std::string::npos) << report;
    EXPECT_FALSE(fs::exists(fs::path(dir_) / "level.json"));
}

TEST_F(SlurmFake, AResumeSubmitsOnlyTheShardsTheStoreLacks) {
    FakeSlurm first(dir_);
    first.failuresLeft[1] = 100;
    EXPECT_FALSE(bakeOnSlurm(dir_, options(0), first, nullptr).merged);
    FakeSlurm again(dir_);
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(0), again, nullptr);
    EXPECT_TRUE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{1}}));
    // Everything there: only the merge is submitted.
    FakeSlurm third(dir_);
    const SlurmBakeResult done = bakeOnSlurm(dir_, options(0), third, nullptr);
    EXPECT_TRUE(done.merged);
    EXPECT_TRUE(done.arrays.empty());
    EXPECT_EQ(done.jobs.size(), 1u);
}

TEST_F(SlurmFake, ALightFieldLevelSubmitsItsPartsAndReportsAFailingPart) {
    LightFieldCookSettings l;
    l.cameras = 4;
    l.imageRes = 8;
    writeList(l, 2); // a probe: 6 slabs x 2 blocks of rows, then its own shard
    const ShardList list = readShardList(dir_);
    ASSERT_EQ(list.shards.size(), 26u);
    std::vector<int> parts;
    for (int i = 0; i < 26; ++i)
        if (i != 12 && i != 25) parts.push_back(i);
    FakeSlurm slurm(dir_);
    slurm.failuresLeft[15] = 100; // room_b_probe's part 2: slab 1 rows 0 .. 1
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(1), slurm, nullptr);
    EXPECT_FALSE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{parts, {15}}));
    // The probe shards were submitted after the parts each time, and cancelled with the
    // merge when a part failed: never run.
    EXPECT_EQ(r.dependentArrays, (std::vector<std::vector<int>>{{12, 25}, {12, 25}}));
    EXPECT_EQ(slurm.cancelled, (std::vector<std::string>{"101", "102", "104", "105"}));
    EXPECT_FALSE(shardPresent(dir_, list.shards[12]));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].index, 15);
    EXPECT_EQ(r.failures[0].probe, "room_b_probe");
    EXPECT_EQ(r.failures[0].part, 2);
    const std::string report = slurmFailureReport(r);
    EXPECT_NE(report.find("shard 15 (probe room_b_probe, part 2: slab 1 rows 0 .. 1): FAILED"),
              std::string::npos)
        << report;
    // The resume submits the one part left; the merge job assembles the probes.
    FakeSlurm again(dir_);
    const SlurmBakeResult resumed = bakeOnSlurm(dir_, options(0), again, nullptr);
    EXPECT_TRUE(resumed.merged);
    EXPECT_EQ(resumed.arrays, (std::vector<std::vector<int>>{{15}}));
    EXPECT_EQ(resumed.dependentArrays, (std::vector<std::vector<int>>{{12, 25}}));
    EXPECT_TRUE(shardPresent(dir_, list.shards[12]));
}

// Array 1 holds the leaves, array 2 (afterok on array 1) the dependents, the merge waits for
// array 2; the scripts both run bake-shard.
TEST_F(SlurmFake, APemBakeRunsTracesThenSamplesThenTheMerge) {
    PemCookSettings p;
    p.samples = 3;
    p.faceRes = 8;
    p.imageWidth = 32, p.imageHeight = 24;
    writeList(p, 0, kBowlRoom);
    FakeSlurm slurm(dir_);
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(0), slurm, nullptr);
    EXPECT_TRUE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1, 2}}));
    EXPECT_EQ(r.dependentArrays, (std::vector<std::vector<int>>{{3, 4, 5}}));
    ASSERT_EQ(r.jobs, (std::vector<std::string>{"100", "101", "102"}));
    auto has = [&](const std::string& job, const std::string& arg) {
        const std::vector<std::string>& argv = slurm.submitted[job];
        return std::find(argv.begin(), argv.end(), arg) != argv.end();
    };
    EXPECT_TRUE(has("100", "--array=0,1,2"));
    EXPECT_TRUE(has("101", "--array=3,4,5"));
    EXPECT_TRUE(has("101", "--dependency=afterok:100"));
    EXPECT_TRUE(has("102", "--dependency=afterok:101"));
    EXPECT_TRUE(slurm.submitted["101"].back().ends_with("dependent.sh"));
    std::ifstream script(fs::path(dir_) / ".shards/slurm/dependent.sh");
    std::stringstream text;
    text << script.rdbuf();
    EXPECT_NE(text.str().find("bake-shard '" + dir_ + "' --shard \"$SLURM_ARRAY_TASK_ID\""),
              std::string::npos)
        << text.str();
}

// A sample shard that fails every time: reported by index and sample, the traces are not
// resubmitted, the merge never runs.
TEST_F(SlurmFake, AFailingPemSampleIsReportedAndOnlyItIsResubmitted) {
    PemCookSettings p;
    p.samples = 2;
    p.faceRes = 8;
    p.imageWidth = 32, p.imageHeight = 24;
    writeList(p, 0, kBowlRoom);
    FakeSlurm slurm(dir_);
    slurm.failuresLeft[3] = 100;
    const SlurmBakeResult r = bakeOnSlurm(dir_, options(1), slurm, nullptr);
    EXPECT_FALSE(r.merged);
    EXPECT_EQ(r.arrays, (std::vector<std::vector<int>>{{0, 1}}));
    EXPECT_EQ(r.dependentArrays, (std::vector<std::vector<int>>{{2, 3}, {3}}));
    ASSERT_EQ(r.failures.size(), 1u);
    EXPECT_EQ(r.failures[0].index, 3);
    EXPECT_EQ(r.failures[0].part, 1);
    const std::string report = slurmFailureReport(r);
    EXPECT_NE(report.find("shard 3 (PEM sample 1: maps): FAILED"), std::string::npos) << report;
    EXPECT_FALSE(fs::exists(fs::path(dir_) / "pem"));
}

// A signal while the shards run: every job submitted (the array and the merge) is cancelled
// in one scancel and waited for; Cancelled names them; the merge never ran, nothing is written.
TEST_F(SlurmFake, ACancelRequestCancelsEveryJobWaitsAndMergesNothing) {
    FakeSlurm slurm(dir_);
    slurm.hold = true;
    slurm.cancelAtPause = 3;
    try {
        bakeOnSlurm(dir_, options(2), slurm, nullptr);
        ADD_FAILURE() << "the bake was not cancelled";
    } catch (const Cancelled& e) {
        EXPECT_NE(std::string(e.what()).find("cancelled jobs 100, 101"), std::string::npos)
            << e.what();
    }
    clearCancelRequest();
    EXPECT_EQ(slurm.scancels, (std::vector<std::vector<std::string>>{{"100", "101"}}));
    EXPECT_FALSE(fs::exists(fs::path(dir_) / "level.json"));
    const ShardList list = readShardList(dir_);
    for (const Shard& s : list.shards)
        EXPECT_FALSE(shardPresent(dir_, s));
}

// `bake --slurm` as a user runs it, against a scheduler of three scripts whose tasks run until
// scancel: SIGINT or SIGTERM exits 130 at once, scancel got both job ids, no level is written.
TEST_F(SlurmFake, ASignalToBakeSlurmCancelsItsJobsAndExits130) {
    const fs::path bin = root_ / "bin";
    fs::create_directories(bin);
    const auto script = [&](const std::string& name, const std::string& body) {
        std::ofstream(bin / name) << "#!/bin/bash\nd=\"$FAKE_SLURM_DIR\"\n" << body;
        fs::permissions(bin / name, fs::perms::owner_all);
    };
    script("sbatch", "id=$(cat \"$d/next\" 2>/dev/null || echo 100)\n"
                     "echo $((id + 1)) > \"$d/next\"\necho \"$id $*\" >> \"$d/sbatch.log\"\n"
                     "for a in \"$@\"; do case \"$a\" in --array=*) s=\"${a#--array=}\"\n"
                     "  echo \"${s%%\\%*}\" > \"$d/$id.array\";; esac; done\necho \"$id\"\n");
    script("squeue",
           "for a in \"$@\"; do case \"$a\" in --jobs=*) j=\"${a#--jobs=}\";; esac; done\n"
           "s=RUNNING; [ -e \"$d/cancelled-$j\" ] && s=CANCELLED\n"
           "if [ -e \"$d/$j.array\" ]; then\n"
           "  for i in $(tr ',' ' ' < \"$d/$j.array\"); do echo \"${j}_$i|$s\"; done\n"
           "else echo \"$j|$s\"; fi\n");
    script("scancel", "echo \"$*\" >> \"$d/scancel.log\"\n"
                      "for j in \"$@\"; do touch \"$d/cancelled-$j\"; done\n");
    const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin:/bin";
    for (const int sig : {SIGINT, SIGTERM}) {
        const fs::path fake = root_ / ("fake-" + std::to_string(sig));
        const fs::path level = root_ / ("level-" + std::to_string(sig));
        fs::create_directories(fake);
        ::setenv("PATH", (bin.string() + ":" + path).c_str(), 1);
        ::setenv("FAKE_SLURM_DIR", fake.c_str(), 1);
        test::Child c(
            fs::path(SPECULA_BIN_DIR) / "specula-cook",
            {"bake", test::kTwoRooms, "--out", level.string(), "--face-res", "8", "--slurm"},
            root_ / "scratch");
        ::setenv("PATH", path.c_str(), 1);
        ::unsetenv("FAKE_SLURM_DIR");
        const auto submitted = [&] {
            std::ifstream log(fake / "sbatch.log");
            int lines = 0;
            for (std::string line; std::getline(log, line);)
                ++lines;
            return lines >= 2; // the array and the merge
        };
        ASSERT_TRUE(c.waitFor(submitted, 120)) << "bake --slurm never submitted its jobs";
        const auto start = std::chrono::steady_clock::now();
        c.signal(sig);
        const test::ChildResult r = c.wait();
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("[slurm-fake] signal %d: exit %d %.3f s after it; stderr: %s", sig, r.status,
                    seconds, r.err.c_str());
        EXPECT_EQ(r.status, 130) << r.err;
        EXPECT_LT(seconds, 5.0);
        EXPECT_EQ(test::slurpFile(fake / "scancel.log"), "100 101\n");
        EXPECT_NE(r.err.find("cancelled jobs 100, 101"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(level / "level.json"));
        EXPECT_FALSE(fs::exists(level.string() + ".lock"));
    }
}

} // namespace
} // namespace specula
