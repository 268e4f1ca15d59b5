// Nothing lost, round two (issue 34): specula-cook reads every value strictly (integers
// decimal, numbers finite, no empty value), reads --config only from a regular file (a FIFO
// must not hang it, /dev/zero not grow it), and fails, with a message, when stdout or an
// output file cannot be written (a full disk: /dev/full) instead of exiting 0 with nothing
// written. Exit 2 names the flag; exit 1 names the file.
#include "support/shell_tool.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include <sys/stat.h>

namespace fs = std::filesystem;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kScenes = SPECULA_TEST_SCENES;
const std::string kRoom = std::string(SPECULA_SOURCE_DIR) + "/assets/room/room.gltf";

using specula::test::lineCount;
using specula::test::shellQuote;
using specula::test::TempDir;
using specula::test::ToolRun;

// Under `timeout`: a run that blocks (on a FIFO) fails with 124 instead of hanging the test.
ToolRun cook(const std::string& args) {
    return specula::test::runShellTool(kCook, args, "timeout 60 ");
}

// The run failed with `status`, one error line naming `mustName`, and printed nothing.
void expectRefused(const ToolRun& r, int status, const std::string& mustName,
                   const std::string& what) {
    EXPECT_EQ(r.status, status) << what << "\n" << r.err;
    EXPECT_NE(r.err.find("error: "), std::string::npos) << what << "\n" << r.err;
    EXPECT_NE(r.err.find(mustName), std::string::npos) << what << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), status == 2 ? 2u : 1u) << what << "\n" << r.err;
}

} // namespace

TEST(StrictInput, ALeadingZeroIsDecimalNotOctal) {
    const TempDir dir("strict-octal");
    const fs::path out = dir.path / "probe";
    const ToolRun r =
        cook("bake " + shellQuote(kRoom) + " --face-res 010 --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(out / "manifest.json");
    const nlohmann::json manifest = nlohmann::json::parse(in);
    EXPECT_EQ(manifest.at("face_res"), 10) << "--face-res 010 was read as octal";
}

TEST(StrictInput, EmptyNaNAndNonDecimalValuesAreRefusedNamingTheFlag) {
    const TempDir dir("strict-values");
    const std::string room = shellQuote(kRoom), d = shellQuote(dir.path.string());
    // Each would have been read as something: '' as shard 0, nan and inf passed CLI::Range,
    // 0x10 as 16.
    expectRefused(cook("bake-shard " + d + " --shard ''"), 2, "--shard", "--shard ''");
    expectRefused(cook("bake-shard " + d + " --shard 0x1"), 2, "--shard", "--shard 0x1");
    for (const char* v : {"nan", "inf", "-inf"}) {
        expectRefused(cook("plan " + room + " --view-share " + v), 2, "--view-share", v);
        expectRefused(cook("farm " + d + " --overhead " + v), 2, "--overhead", v);
    }
    expectRefused(cook("farm " + d + " --nodes 4,0x10"), 2, "--nodes", "--nodes 4,0x10");
    expectRefused(cook("farm " + d + " --csv ''"), 2, "--csv", "--csv ''");
    expectRefused(cook("plan " + room + " --seed -1"), 2, "--seed", "--seed -1");
    expectRefused(cook("inspect ''"), 2, "FILE", "inspect ''");
}

TEST(StrictInput, ConfigIsReadOnlyFromARegularFile) {
    const TempDir dir("strict-config");
    const fs::path fifo = dir.path / "config.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string out = shellQuote((dir.path / "probe").string());
    // Each is refused before the scene is read: a FIFO blocked the run forever (here: until
    // the timeout's 124), /dev/zero filled memory, a folder was read as an empty config.
    for (const fs::path& bad : {fifo, fs::path("/dev/zero"), dir.path}) {
        const std::string q = shellQuote(bad.string());
        expectRefused(cook("--config " + q + " bake " + shellQuote(kRoom) + " --out " + out), 2,
                      bad.string(), "--config " + bad.string());
        expectRefused(cook("bake " + shellQuote(kRoom) + " --out " + out + " --config " + q), 2,
                      "--config", "bake ... --config " + bad.string());
    }
    expectRefused(cook("--config '' inspect " + shellQuote(kRoom)), 2, "--config", "''");
    EXPECT_FALSE(fs::exists(dir.path / "probe"));
    // A regular config file still works, and its integers are decimal too.
    const fs::path config = dir.path / "bake.toml";
    std::ofstream(config) << "[bake]\nface-res = 010\n";
    ASSERT_EQ(cook("--config " + shellQuote(config.string()) + " bake " + shellQuote(kRoom) +
                   " --out " + out)
                  .status,
              0);
    std::ifstream in(dir.path / "probe" / "manifest.json");
    EXPECT_EQ(nlohmann::json::parse(in).at("face_res"), 10);
}

TEST(StrictInput, AFullStdoutFailsTheRunWithAMessage) {
    // /dev/full: every write fails with ENOSPC, as on a full disk. Exit 0 with an empty
    // output is what a script must never get.
    const ToolRun inspect =
        cook("inspect " + shellQuote((kScenes / "box/Box.glb").string()) + " >/dev/full");
    expectRefused(inspect, 1, "standard output", "inspect >/dev/full");
    EXPECT_NE(inspect.err.find("No space left on device"), std::string::npos) << inspect.err;
    const ToolRun plan = cook("plan " + shellQuote(kRoom) + " --plan analytic --json >/dev/full");
    expectRefused(plan, 1, "standard output", "plan --json >/dev/full");
    // --help too: its text is the output.
    expectRefused(cook("bake --help >/dev/full"), 1, "standard output", "bake --help");
    // The same runs to a working stdout succeed: the failure is the write's.
    EXPECT_EQ(cook("plan " + shellQuote(kRoom) + " --plan analytic --json").status, 0);
}

TEST(StrictInput, AFarmTableThatCannotBeWrittenFailsTheRun) {
    const TempDir dir("strict-farm");
    const std::string level = shellQuote((dir.path / "level").string());
    ASSERT_EQ(
        cook("shards " + shellQuote(specula::test::kTwoRooms) + " --out " + level + " --face-res 8")
            .status,
        0);
    for (const char* shard : {"0", "1"})
        ASSERT_EQ(cook("bake-shard " + level + " --shard " + shard).status, 0);
    const ToolRun full = cook("farm " + level + " --csv /dev/full");
    expectRefused(full, 1, "/dev/full", "farm --csv /dev/full");
    EXPECT_NE(full.err.find("No space left on device"), std::string::npos) << full.err;
    // A device is written in place, never replaced by a rename.
    struct stat st {};
    ASSERT_EQ(::stat("/dev/full", &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << "/dev/full was replaced";
    // A regular file is written whole.
    const fs::path csv = dir.path / "farm.csv";
    ASSERT_EQ(cook("farm " + level + " --csv " + shellQuote(csv.string())).status, 0);
    EXPECT_EQ(specula::test::fileLines(csv).size(), 5u); // header + 4 node counts
}
