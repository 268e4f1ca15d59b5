// specula-sandbox level --roughness through the shell, on the bundled two-room scene: the
// walk compares the level's glossy lookup and its mirror lookup with the GGX truth (frames.csv
// gains the mirror lookup's column, summary.csv its row), logs the chains' memory, and times
// the glossy level beside the mirror level in the same rounds; a roughness outside [0, 1] is
// a usage error naming the flag and leaves no folder.
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kTwoRooms = fs::path(SPECULA_SOURCE_DIR) / "assets/two_rooms/two_rooms.gltf";

using namespace specula::test;

const ToolSubcommand level{fs::path(SPECULA_BIN_DIR) / "specula-sandbox", "level"};

TEST(SandboxLevelGlossy, RoughnessComparesGlossyAndMirrorLookupsAndTimesBoth) {
    TempDir dir("level-glossy");
    const fs::path out = dir.path / "out";
    const ToolRun r =
        level(shellQuote(kTwoRooms.string()) + " --frames 3 --size 64x48 --face-res 32 " +
              "--sky '' --roughness 0.2 --samples 16 --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> frames = fileLines(out / "frames.csv");
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_NE(frames[0].find(",psnr_visibility_mirror_lookup"), std::string::npos) << frames[0];
    const std::vector<std::string> summary = fileLines(out / "summary.csv");
    ASSERT_GE(summary.size(), 5u);
    EXPECT_EQ(summary[4].rfind("visibility (mirror lookup),", 0), 0u) << summary[4];
    EXPECT_NE(r.out.find("MiB of chains (2 probes) at roughness 0.2"), std::string::npos) << r.out;
    // The 1 + 1 + 3 + 3 rows of a mirror walk, and the mirror level's visibility K = 4 row.
    const std::vector<std::string> timing = fileLines(out / "timing.csv");
    ASSERT_EQ(timing.size(), 10u);
    EXPECT_EQ(timing[9].rfind("visibility (mirror),4,", 0), 0u) << timing[9];

    const ToolRun bad = level(shellQuote(kTwoRooms.string()) + " --roughness 1.5 --out " +
                              shellQuote((dir.path / "bad").string()));
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_NE(bad.err.find("--roughness"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir.path / "bad"));
}

} // namespace
