// What `specula-cook bake --out DIR` may replace, and how it stops (issue 10, items 1-3):
// a folder that is not a Specula probe, a probe folder holding a file Specula did not write,
// and a folder holding the input scene are refused and left byte for byte; SIGINT/SIGTERM
// before the final rename leave the previous probe, exit 130 and no temporary folder; what a
// killed bake left beside DIR is cleaned by the next bake with a line; a write past a
// file-size limit (a full disk) fails the bake and leaves DIR as it was; a signal to
// bake-shard (scancel) leaves its shard store as it was. A temporary folder is removed only
// when its owner file names this host and a process that no longer runs (issue 34); what a
// SIGKILLed merge left is removed by the next merge.
#include "engine/core/host_name.h"
#include "tests/support/child_process.h"
#include "tests/support/scratch_dir_test.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using specula::test::Child;
using specula::test::ChildOptions;
using specula::test::ChildResult;
using specula::test::slurpFile;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kRoomDir = fs::path(SPECULA_SOURCE_DIR) / "assets" / "room";
const fs::path kRoom = kRoomDir / "room.gltf";

// Every file below `dir`, relative path -> bytes ("<dir>" for folders).
std::map<std::string, std::string> snapshot(const fs::path& dir) {
    std::map<std::string, std::string> s;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        s[fs::relative(e.path(), dir).string()] =
            e.is_regular_file() ? slurpFile(e.path()) : "<dir>";
    return s;
}

// Names beside `dir` that a bake leaves only while it runs.
std::vector<std::string> temporariesBeside(const fs::path& dir) {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir.parent_path())) {
        const std::string name = e.path().filename().string();
        if (name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos)
            found.push_back(name);
    }
    return found;
}

class OutputSafety : public specula::test::ScratchDirTest {
protected:
    OutputSafety() : ScratchDirTest("specula-output-safety") {}

    ChildResult bake(const fs::path& scene, const fs::path& out, const std::string& faceRes = "4",
                     const ChildOptions& o = {}) {
        const ChildResult r = specula::test::runChild(
            kCook, {"bake", scene.string(), "--out", out.string(), "--face-res", faceRes},
            root_ / "scratch", o);
        std::printf("[output-safety] bake --out %s: exit %d, stdout: %s\n  stderr: %s",
                    out.filename().c_str(), r.status, r.out.substr(0, r.out.find('\n')).c_str(),
                    r.err.empty() ? "(empty)\n" : r.err.c_str());
        return r;
    }
    // A cooked probe at root/name, baked now.
    fs::path bakedProbe(const std::string& name) {
        const fs::path p = root_ / name;
        EXPECT_EQ(bake(kRoom, p).status, 0);
        EXPECT_TRUE(fs::exists(p / "manifest.json"));
        return p;
    }
    // A bake into `dir` must be refused with exit 1 and one error line naming `mustName`,
    // leaving `dir` exactly as it was.
    void expectRefused(const fs::path& scene, const fs::path& dir, const std::string& mustName) {
        const auto before = snapshot(dir);
        const ChildResult r = bake(scene, dir);
        EXPECT_EQ(r.status, 1) << r.err;
        EXPECT_NE(r.err.find(mustName), std::string::npos) << "must name " << mustName;
        EXPECT_TRUE(snapshot(dir) == before) << "the refused folder changed";
        EXPECT_TRUE(temporariesBeside(dir).empty());
    }
};

} // namespace

TEST_F(OutputSafety, FolderWhoseManifestIsNotASpeculaProbeIsRefused) {
    // The web folder from the issue: it has a manifest.json, but not ours.
    const fs::path web = root_ / "web";
    fs::create_directories(web);
    std::ofstream(web / "manifest.json") << R"({"name": "web"})";
    std::ofstream(web / "index.html") << "<html>keep me</html>";
    expectRefused(kRoom, web, "manifest.json");
    // Not JSON at all, and a manifest.json that is a folder: not probes either.
    std::ofstream(web / "manifest.json") << "<<not json>>";
    expectRefused(kRoom, web, "manifest.json");
    fs::remove(web / "manifest.json");
    fs::create_directories(web / "manifest.json");
    expectRefused(kRoom, web, "manifest.json");
}

TEST_F(OutputSafety, FolderHoldingTheInputSceneIsNeverReplaced) {
    // The scene's folder with a real probe manifest copied into it (issue 10, item 1).
    const fs::path probe = bakedProbe("probe");
    const fs::path scene = root_ / "scene";
    fs::copy(kRoomDir, scene);
    fs::copy_file(probe / "manifest.json", scene / "manifest.json");
    expectRefused(scene / "room.gltf", scene, "input scene");
    // A folder above the scene's (scratch files live elsewhere), and the scene's folder
    // named with a trailing separator.
    const fs::path above = root_ / "above";
    fs::create_directories(above);
    fs::rename(scene, above / "scene");
    expectRefused(above / "scene" / "room.gltf", above, "input scene");
    fs::rename(above / "scene", scene);
    expectRefused(scene / "room.gltf", fs::path(scene.string() + "/"), "input scene");
    EXPECT_TRUE(fs::exists(scene / "room.bin"));
}

TEST_F(OutputSafety, ProbeFolderWithAForeignFileIsRefusedNamingIt) {
    const fs::path probe = bakedProbe("probe");
    std::ofstream(probe / "notes.txt") << "a user's notes";
    expectRefused(kRoom, probe, "notes.txt");
    fs::remove(probe / "notes.txt");
    fs::create_directories(probe / "extra");
    expectRefused(kRoom, probe, "extra");
    fs::remove(probe / "extra");
    // Without the foreign entries the same folder is replaced as before.
    EXPECT_EQ(bake(kRoom, probe).status, 0);
    EXPECT_TRUE(temporariesBeside(probe).empty());

    // A manifest forged to list a user's file (issue 34): listing it does not make it ours.
    // Without a checksum, or with one that does not match its bytes, the file is no texture
    // Specula wrote; the folder is refused and the file kept.
    const fs::path manifest = probe / "manifest.json";
    const std::string original = [&] {
        std::ifstream in(manifest);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }();
    for (const std::string& checksum : {std::string(), std::string("fnv1a64:0000000000000000")}) {
        nlohmann::json forged = nlohmann::json::parse(original);
        forged["layers"][0]["file"] = "thesis.docx";
        if (checksum.empty())
            forged["layers"][0].erase("checksum");
        else
            forged["layers"][0]["checksum"] = checksum;
        std::ofstream(manifest) << forged.dump(2);
        std::ofstream(probe / "thesis.docx") << "four years of work";
        fs::remove(probe / "layer_00.ktx2");
        expectRefused(kRoom, probe, "thesis.docx");
        EXPECT_TRUE(fs::exists(probe / "thesis.docx")) << checksum;
        fs::remove(probe / "thesis.docx");
    }
}

TEST_F(OutputSafety, EmptyFolderAndMissingFolderAreFilled) {
    const fs::path empty = root_ / "empty";
    fs::create_directories(empty);
    EXPECT_EQ(bake(kRoom, empty).status, 0);
    EXPECT_TRUE(fs::exists(empty / "manifest.json"));
    EXPECT_EQ(bake(kRoom, root_ / "new" / "nested").status, 0);
    EXPECT_TRUE(fs::exists(root_ / "new" / "nested" / "manifest.json"));
}

TEST_F(OutputSafety, SignalBeforeTheFinalRenameLeavesThePreviousProbe) {
    const fs::path probe = bakedProbe("probe");
    const auto before = snapshot(probe);
    for (int sig : {SIGINT, SIGTERM}) {
        // The test hook holds the finished temporary folder before the commit check, so the
        // signal lands in the write phase, after every file is written and before the rename.
        Child c(kCook, {"bake", kRoom.string(), "--out", probe.string(), "--face-res", "16"},
                root_ / "scratch", {{"SPECULA_TEST_PAUSE_BEFORE_COMMIT=60"}});
        const fs::path staged =
            fs::path(probe.string() + ".tmp-" + std::to_string(c.pid())) / "manifest.json";
        ASSERT_TRUE(c.waitFor([&] { return fs::exists(staged); }, 120))
            << "the bake never staged its manifest";
        const auto t0 = std::chrono::steady_clock::now();
        c.signal(sig);
        const ChildResult r = c.wait();
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf("[output-safety] %s in the write phase: exit %d %.3f s after the signal, "
                    "stderr: %s",
                    sig == SIGINT ? "SIGINT" : "SIGTERM", r.status, s, r.err.c_str());
        EXPECT_EQ(r.status, 130) << r.err;
        EXPECT_NE(r.err.find("cancelled"), std::string::npos) << r.err;
        EXPECT_LT(s, 5.0) << "the pause must end at the signal";
        EXPECT_TRUE(snapshot(probe) == before) << "the previous probe must stay";
        EXPECT_TRUE(temporariesBeside(probe).empty());
    }
    // The hook alone (no signal) changes nothing: the bake commits after the pause.
    const ChildResult r = bake(kRoom, probe, "16", {{"SPECULA_TEST_PAUSE_BEFORE_COMMIT=0.1"}});
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(snapshot(probe) == before);
}

TEST_F(OutputSafety, SignalWhileLayersAreWrittenLeavesThePreviousProbe) {
    // No hook: the signal goes as soon as the first layer file of a large bake is staged;
    // the remaining layers take far longer to encode than the signal takes to arrive.
    const fs::path probe = bakedProbe("probe");
    const auto before = snapshot(probe);
    Child c(kCook, {"bake", kRoom.string(), "--out", probe.string(), "--face-res", "512"},
            root_ / "scratch");
    const fs::path staged = fs::path(probe.string() + ".tmp-" + std::to_string(c.pid()));
    ASSERT_TRUE(c.waitFor([&] { return fs::exists(staged / "layer_00.ktx2"); }, 300));
    c.signal(SIGTERM);
    const ChildResult r = c.wait();
    EXPECT_EQ(r.status, 130) << r.err;
    EXPECT_TRUE(snapshot(probe) == before);
    EXPECT_TRUE(temporariesBeside(probe).empty());
}

// The owner file a writer puts in its temporary folder first (temporary_owner.h).
static void writeOwner(const fs::path& folder, const std::string& host, long long pid) {
    std::ofstream(folder / ".specula-owner") << "host " << host << "\npid " << pid << "\n";
}

TEST_F(OutputSafety, TemporariesOfDeadProcessesAreCleanedWithALine) {
    const fs::path probe = bakedProbe("probe");
    const pid_t dead = specula::test::deadPid(), dead2 = specula::test::deadPid(),
                dead3 = specula::test::deadPid();
    const fs::path staleTmp = probe.string() + ".tmp-" + std::to_string(dead);
    const fs::path staleOld = probe.string() + ".old-" + std::to_string(dead);
    const fs::path live = probe.string() + ".tmp-" + std::to_string(::getpid());
    // A dead pid here, but another machine's folder (a shared disk), and one with no owner.
    const fs::path foreign = probe.string() + ".tmp-" + std::to_string(dead2);
    const fs::path unowned = probe.string() + ".tmp-" + std::to_string(dead3);
    for (const fs::path& p : {staleTmp, staleOld, live, foreign, unowned}) {
        fs::create_directories(p);
        std::ofstream(p / "layer_00.ktx2") << std::string(4096, 'x');
    }
    writeOwner(staleTmp, specula::hostName(), dead);
    writeOwner(staleOld, specula::hostName(), dead);
    writeOwner(live, specula::hostName(), ::getpid());
    writeOwner(foreign, "other-node-7", dead2);
    std::ofstream(probe.string() + ".tmp-" + std::to_string(dead) + "x") << "not ours";
    const ChildResult r = bake(kRoom, probe);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(fs::exists(staleTmp));
    EXPECT_FALSE(fs::exists(staleOld));
    EXPECT_NE(r.out.find("removed stale " + staleTmp.string()), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("removed stale " + staleOld.string()), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(live / "layer_00.ktx2")) << "a live process's folder is never touched";
    EXPECT_TRUE(fs::exists(probe.string() + ".tmp-" + std::to_string(dead) + "x"));
    EXPECT_TRUE(fs::exists(foreign / "layer_00.ktx2")) << "another host's folder is never touched";
    EXPECT_NE(r.out.find("left " + foreign.string() + " as it is: it belongs to process " +
                         std::to_string(dead2) + " on host other-node-7"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(unowned / "layer_00.ktx2")) << "a folder of unknown owner is left";
    EXPECT_NE(r.out.find("left " + unowned.string() + " as it is: it has no owner file"),
              std::string::npos)
        << r.out;
    for (const fs::path& p : {live, foreign, unowned})
        fs::remove_all(p);

    // Killed between the two renames of the fallback swap: DIR is missing and DIR.old-PID
    // holds the previous probe; the next bake puts it back before it starts.
    fs::rename(probe, staleOld);
    writeOwner(staleOld, specula::hostName(), dead);
    const ChildResult again = bake(kRoom, probe);
    EXPECT_EQ(again.status, 0) << again.err;
    EXPECT_NE(again.out.find("restored " + probe.string()), std::string::npos) << again.out;
    EXPECT_FALSE(fs::exists(staleOld));
}

TEST_F(OutputSafety, ShortWriteFailsTheBakeAndLeavesThePreviousProbe) {
    const fs::path probe = bakedProbe("probe");
    const auto before = snapshot(probe);
    // 4 KiB per file: the first 64^2 layer cannot be written (EFBIG, as on a full disk).
    ChildOptions limited;
    limited.fileSizeLimit = 4096;
    const ChildResult r = bake(kRoom, probe, "64", limited);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_TRUE(snapshot(probe) == before);
    EXPECT_TRUE(temporariesBeside(probe).empty());
    // A failed bake removes the folders it created for --out.
    const ChildResult nested = bake(kRoom, root_ / "made" / "by" / "bake", "64", limited);
    EXPECT_EQ(nested.status, 1);
    EXPECT_FALSE(fs::exists(root_ / "made"));
}

TEST_F(OutputSafety, HelpStatesTheCancelledExitStatus) {
    const ChildResult r = specula::test::runChild(kCook, {"bake", "--help"}, root_ / "scratch");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("130 cancelled"), std::string::npos) << r.out;
}

TEST_F(OutputSafety, SignalToABakeShardLeavesTheStoreAsItWas) {
    // scancel sends SIGTERM to a Slurm task: the shard must not reach the store half-written,
    // nor leave its temporary folder there, and a re-run bakes it.
    const fs::path twoRooms =
        fs::path(SPECULA_SOURCE_DIR) / "assets" / "two_rooms" / "two_rooms.gltf";
    const fs::path level = root_ / "level", store = level / ".shards";
    ChildResult r = specula::test::runChild(
        kCook, {"shards", twoRooms.string(), "--out", level.string(), "--face-res", "16"},
        root_ / "scratch");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto storeNames = [&] {
        std::set<std::string> names;
        for (const auto& e : fs::directory_iterator(store))
            names.insert(e.path().filename().string());
        return names;
    };
    const std::set<std::string> before = storeNames();
    for (int sig : {SIGTERM, SIGINT}) {
        Child c(kCook, {"bake-shard", level.string(), "--shard", "0"}, root_ / "scratch",
                {{"SPECULA_TEST_PAUSE_BEFORE_COMMIT=60"}});
        const std::string staged = ".tmp-" + std::to_string(c.pid());
        ASSERT_TRUE(c.waitFor(
            [&] {
                for (const auto& e : fs::directory_iterator(store))
                    if (e.path().filename().string().find(staged) != std::string::npos &&
                        fs::exists(e.path() / "manifest.json"))
                        return true;
                return false;
            },
            120))
            << "the shard never staged its manifest";
        c.signal(sig);
        r = c.wait();
        EXPECT_EQ(r.status, 130) << r.err;
        EXPECT_NE(r.err.find("cancelled"), std::string::npos) << r.err;
        EXPECT_TRUE(storeNames() == before) << "a cancelled shard left something in the store";
    }
    r = specula::test::runChild(kCook, {"bake-shard", level.string(), "--shard", "0"},
                                root_ / "scratch");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(storeNames().size(), before.size() + 3) << "the shard, its checksums and its time";
}

TEST_F(OutputSafety, WhatAKilledMergeLeftIsRemovedByTheNextMerge) {
    // SIGKILL (no handler runs) while the merge holds a staged probe folder: its temporary
    // stays beside the probe's place, owned by a process that no longer runs.
    const fs::path twoRooms =
        fs::path(SPECULA_SOURCE_DIR) / "assets" / "two_rooms" / "two_rooms.gltf";
    const fs::path level = root_ / "level";
    ASSERT_EQ(specula::test::runChild(
                  kCook, {"shards", twoRooms.string(), "--out", level.string(), "--face-res", "8"},
                  root_ / "scratch")
                  .status,
              0);
    for (const char* shard : {"0", "1"})
        ASSERT_EQ(specula::test::runChild(kCook, {"bake-shard", level.string(), "--shard", shard},
                                          root_ / "scratch")
                      .status,
                  0);
    Child merge(kCook, {"merge", level.string()}, root_ / "scratch",
                {{"SPECULA_TEST_PAUSE_BEFORE_COMMIT=60"}});
    const fs::path staged = level / ("room_a_probe.tmp-" + std::to_string(merge.pid()));
    ASSERT_TRUE(merge.waitFor([&] { return fs::exists(staged / "manifest.json"); }, 120))
        << "the merge never staged room_a_probe";
    merge.signal(SIGKILL);
    EXPECT_EQ(merge.wait().status, 128 + SIGKILL);
    ASSERT_TRUE(fs::exists(staged)) << "SIGKILL left the staged folder";
    EXPECT_FALSE(fs::exists(level / "level.json"));
    const ChildResult r =
        specula::test::runChild(kCook, {"merge", level.string()}, root_ / "scratch");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("removed stale " + staged.string()), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(staged));
    EXPECT_TRUE(fs::exists(level / "level.json"));
    EXPECT_TRUE(temporariesBeside(level / "level.json").empty());
}

TEST_F(OutputSafety, TemporaryFilesOfDeadWritersAreRemovedByTheNextLevelBake) {
    // A file written beside and renamed (file_write.h) by a writer killed before the rename
    // names its host and process: PATH.tmp-HOST-PID. The next writer of the level removes this
    // host's dead writer's, and leaves another host's, a live writer's and an unnamed one.
    const fs::path twoRooms =
        fs::path(SPECULA_SOURCE_DIR) / "assets" / "two_rooms" / "two_rooms.gltf";
    const fs::path level = root_ / "level";
    const std::vector<std::string> bakeArgs{"bake",         twoRooms.string(), "--out",
                                            level.string(), "--face-res",      "8"};
    ASSERT_EQ(specula::test::runChild(kCook, bakeArgs, root_ / "scratch").status, 0);
    const pid_t dead = specula::test::deadPid();
    const std::string index = (level / "level.json").string();
    const fs::path stale = index + ".tmp-" + specula::hostName() + "-" + std::to_string(dead),
                   foreign = index + ".tmp-other-node-7-" + std::to_string(dead),
                   live = index + ".tmp-" + specula::hostName() + "-" + std::to_string(::getpid()),
                   unnamed = index + ".tmp-" + std::to_string(dead);
    for (const fs::path& p : {stale, foreign, live, unnamed})
        std::ofstream(p) << "{\"half\": ";
    const ChildResult r = specula::test::runChild(kCook, bakeArgs, root_ / "scratch");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_NE(r.out.find("removed stale " + stale.string() + " (left by process " +
                         std::to_string(dead) + " on this host, which no longer runs)"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(foreign));
    EXPECT_NE(r.out.find("left " + foreign.string() + " as it is: it belongs to process " +
                         std::to_string(dead) + " on host other-node-7"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(live));
    EXPECT_NE(r.out.find("left " + live.string() + " as it is: its process " +
                         std::to_string(::getpid()) + " still runs"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(unnamed));
    EXPECT_NE(r.out.find("left " + unnamed.string() +
                         " as it is: a temporary file, which names "
                         "no host"),
              std::string::npos)
        << r.out;
}
