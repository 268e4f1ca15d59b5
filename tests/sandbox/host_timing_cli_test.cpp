// specula-sandbox host: the host API's path (a host's own program over the reflector meshes,
// DistanceHostProbe::bindTo per draw) draws exactly the sandbox's frame of the same probe and
// view, bit for bit, and both passes get timing rows with their spread. The times themselves
// are the bench's (a ratio on this machine), not asserted here. A probe that cannot be read is
// an error naming it, and no output folder is left.
#include "support/csv_table.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace fs = std::filesystem;

namespace {

using namespace specula::test;

const fs::path kSandbox = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

TEST(SandboxHost, TheHostPathDrawsTheSandboxFrameAndBothAreTimed) {
    TempDir dir("sandbox-host");
    const fs::path out = dir.path / "out";
    const ToolRun r = runShellTool(kSandbox, "host " + shellQuote(kRoom.string()) + " --out " +
                                                 shellQuote(out.string()) +
                                                 " --size 160x120 --face-res 32 --rounds 3");
    ASSERT_EQ(r.status, 0) << r.err << r.out;
    const CsvTable rows = readCsv(out / "host.csv");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("path"), "sandbox");
    EXPECT_EQ(rows[1].at("path"), "host");
    for (const CsvRow& row : rows) {
        EXPECT_EQ(row.at("psnr_to_sandbox"), "inf") << "the same probe, view and shader text";
        EXPECT_EQ(num(row, "frames"), 3.0);
        EXPECT_LE(num(row, "ms_q1"), num(row, "ms_median"));
        EXPECT_LE(num(row, "ms_median"), num(row, "ms_q3"));
        EXPECT_GT(num(row, "ms_median"), 0.0);
    }
    EXPECT_EQ(num(rows[0], "ratio_to_sandbox"), 1.0);
    EXPECT_TRUE(fs::is_regular_file(out / "host.png"));
    EXPECT_NE(r.out.find("ratio to sandbox"), std::string::npos) << r.out;
}

TEST(SandboxHost, AProbeThatCannotBeReadIsAnErrorNamingIt) {
    TempDir dir("sandbox-host-bad");
    const fs::path out = dir.path / "out", missing = dir.path / "none" / "manifest.json";
    const ToolRun r = runShellTool(kSandbox, "host " + shellQuote(kRoom.string()) + " --out " +
                                                 shellQuote(out.string()) + " --probe " +
                                                 shellQuote(missing.string()));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "a failed run leaves no output folder";
}

} // namespace
