// specula-sandbox level through the shell, on the bundled two-room scene (a probe per room,
// influences overlapping at the doorway): it bakes the level, walks the mirror sphere from
// one probe to the other and writes a frame row per frame with a PSNR per blend, and a
// summary row per blend; bad paths are usage errors naming the flag and leave no folder.
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kTwoRooms = fs::path(SPECULA_SOURCE_DIR) / "assets/two_rooms/two_rooms.gltf";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

using namespace specula::test;

// specula-sandbox level ARGS through the shell.
const ToolSubcommand level{fs::path(SPECULA_BIN_DIR) / "specula-sandbox", "level"};

TEST(SandboxLevel, WalksThroughBothRoomsAndWritesAFrameRowPerFrame) {
    TempDir dir("level-walk");
    const fs::path out = dir.path / "out";
    const ToolRun r = level(shellQuote(kTwoRooms.string()) + " --frames 5 --size 64x48 " +
                            "--face-res 32 --sky '' --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "level/level.json"));
    EXPECT_TRUE(fs::exists(out / "level/room_a_probe/manifest.json"));
    EXPECT_TRUE(fs::exists(out / "level/room_b_probe/manifest.json"));
    const std::vector<std::string> frames = fileLines(out / "frames.csv");
    ASSERT_EQ(frames.size(), 6u);
    EXPECT_EQ(frames[0].rfind("frame,x,y,z,psnr_nearest,psnr_engine,psnr_visibility", 0), 0u);
    // The walk starts at room A's probe (x = -3) and ends at room B's (x = 3).
    EXPECT_EQ(frames[1].rfind("0,-3,1.2,0,", 0), 0u) << frames[1];
    EXPECT_EQ(frames[5].rfind("4,3,1.2,0,", 0), 0u) << frames[5];
    EXPECT_NE(frames[1].find("room_a_probe:1.000"), std::string::npos) << frames[1];
    EXPECT_NE(frames[5].find("room_b_probe:1.000"), std::string::npos) << frames[5];
    const std::vector<std::string> summary = fileLines(out / "summary.csv");
    ASSERT_GE(summary.size(), 4u);
    EXPECT_EQ(summary[1].rfind("nearest,", 0), 0u);
    EXPECT_EQ(summary[2].rfind("engine,", 0), 0u);
    EXPECT_EQ(summary[3].rfind("visibility,", 0), 0u);
    EXPECT_NE(r.out.find("visibility"), std::string::npos);
    // The GPU pass of every blend and K, against envmap: a header and 1 + 1 + 3 + 3 rows, the
    // envmap row the unit of the ratios.
    const std::vector<std::string> timing = fileLines(out / "timing.csv");
    ASSERT_EQ(timing.size(), 9u);
    EXPECT_EQ(timing[0].rfind("blend,k,ms_median,ratio_to_envmap", 0), 0u);
    EXPECT_EQ(timing[1].rfind("envmap (one probe),1,", 0), 0u) << timing[1];
    EXPECT_NE(timing[1].find(",1,"), std::string::npos) << timing[1];
    EXPECT_EQ(timing[8].rfind("visibility,4,", 0), 0u) << timing[8];
}

TEST(SandboxLevel, APathFileGivesThePointsAndNoTimingLeavesOutTheGpuPass) {
    TempDir dir("level-path-file");
    const fs::path out = dir.path / "out";
    const fs::path pathFile = dir.path / "path.txt";
    std::ofstream(pathFile) << "# along room A\n-3,1.2,0\n\n  -1,1.2,0.5  \n";
    const ToolRun r = level(shellQuote(kTwoRooms.string()) + " --frames 2 --size 32x24 " +
                            "--face-res 16 --sky '' --no-timing --path @" +
                            shellQuote(pathFile.string()) + " --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> frames = fileLines(out / "frames.csv");
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(frames[1].rfind("0,-3,1.2,0,", 0), 0u) << frames[1];
    EXPECT_EQ(frames[2].rfind("1,-1,1.2,0.5,", 0), 0u) << frames[2];
    EXPECT_FALSE(fs::exists(out / "timing.csv"));
    // A bad line is a usage error naming the file and the line.
    std::ofstream(pathFile) << "-3,1.2,0\n1,2\n";
    const ToolRun bad =
        level(shellQuote(kTwoRooms.string()) + " --path @" + shellQuote(pathFile.string()) +
              " --out " + shellQuote((dir.path / "bad").string()));
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_NE(bad.err.find("path.txt line 2"), std::string::npos) << bad.err;
    EXPECT_FALSE(fs::exists(dir.path / "bad"));
}

TEST(SandboxLevel, BadPathsAreUsageErrorsNamingTheFlagAndLeaveNoFolder) {
    TempDir dir("level-bad");
    for (const std::string& args :
         {std::string("--path '1,2;3,4,5'"), std::string("--k 0"), std::string("--frames 1")}) {
        const fs::path out = dir.path / "out";
        const ToolRun r = level(shellQuote(kTwoRooms.string()) + " " + args + " --out " +
                                shellQuote(out.string()));
        EXPECT_EQ(r.status, 2) << args << ": " << r.err;
        const std::string flag = args.substr(0, args.find(' '));
        EXPECT_NE(r.err.find("error: " + flag + ":"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << args;
    }
    // The room has one probe: a walk through "every probe" needs a path.
    const fs::path out = dir.path / "one";
    const ToolRun r = level(shellQuote(kRoom.string()) + " --frames 2 --size 32x24 --face-res 8 " +
                            "--out " + shellQuote(out.string()));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("--path"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

} // namespace
