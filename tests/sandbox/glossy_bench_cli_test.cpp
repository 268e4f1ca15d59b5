// specula-sandbox glossy through the shell, on the room at a small size: it bakes the two
// probes, writes a row per roughness and method to glossy.csv, the two rectified modes agree
// at roughness 0 (both are the mirror search's lookup there), and a bad --roughness is a usage
// error naming the flag that leaves no folder.
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

using namespace specula::test;

// specula-sandbox glossy ARGS through the shell.
const ToolSubcommand glossy{fs::path(SPECULA_BIN_DIR) / "specula-sandbox", "glossy"};

// The fields after roughness and method of the row of `roughness` and `method` (psnr,
// noise_floor_psnr, ratio_to_envmap, memory_mib); empty when there is no such row.
std::string fieldsOf(const std::vector<std::string>& rows, const std::string& roughness,
                     const std::string& method) {
    const std::string prefix = roughness + ",\"" + method + "\",";
    for (const std::string& row : rows)
        if (row.rfind(prefix, 0) == 0) return row.substr(prefix.size());
    return {};
}

// The psnr and noise_floor_psnr fields of that row.
std::string valuesOf(const std::vector<std::string>& rows, const std::string& roughness,
                     const std::string& method) {
    const std::string fields = fieldsOf(rows, roughness, method);
    return fields.substr(0, fields.find(',', fields.find(',') + 1));
}

TEST(SandboxGlossy, WritesARowPerRoughnessAndMethodAndTheRectifiedModesAgreeAtRoughnessZero) {
    TempDir dir("glossy-bench");
    const fs::path out = dir.path / "out";
    const ToolRun r = glossy(shellQuote(kRoom.string()) + " --roughness 0,0.2 --size 64x48 " +
                             "--face-res 32 --samples 32 --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(fs::exists(out / "probes/distance/manifest.json"));
    EXPECT_TRUE(fs::exists(out / "probes/lightfield/manifest.json"));
    const std::vector<std::string> rows = fileLines(out / "glossy.csv");
    ASSERT_EQ(rows.size(), 1u + 2u * 6u);
    EXPECT_EQ(rows[0], "roughness,method,psnr,noise_floor_psnr,ratio_to_envmap,memory_mib");
    for (const std::string roughness : {"0", "0.2"})
        for (const std::string method :
             {"envmap+chain", "boxproj+chain", "rectified (roughness level)",
              "rectified (footprint level)", "layered (footprint level)", "light field glossy"})
            EXPECT_FALSE(valuesOf(rows, roughness, method).empty()) << roughness << " " << method;
    // At roughness 0 both rectified modes are the secant search's mirror lookup, bit for bit;
    // the truth is exact there (no noise), and noisy but measured at 0.2.
    const std::string level = valuesOf(rows, "0", "rectified (roughness level)");
    EXPECT_EQ(level, valuesOf(rows, "0", "rectified (footprint level)"));
    EXPECT_EQ(level.substr(level.find(',') + 1), "inf");
    const std::string rough = valuesOf(rows, "0.2", "rectified (footprint level)");
    const std::string noise = rough.substr(rough.find(',') + 1);
    EXPECT_NE(noise, "inf");
    EXPECT_NE(noise, "none");
    EXPECT_GT(std::stod(noise), 10.0) << rough;
    // The cost columns: the roughness-level search has no shader, so no pass time; the
    // footprint level's shader is timed against the mirror envmap; both hold memory.
    const std::string cpuOnly = fieldsOf(rows, "0.2", "rectified (roughness level)");
    const std::string shaded = fieldsOf(rows, "0.2", "rectified (footprint level)");
    EXPECT_NE(cpuOnly.find(",none,"), std::string::npos) << cpuOnly;
    EXPECT_EQ(shaded.find("none"), std::string::npos) << shaded;
    EXPECT_GT(std::stod(shaded.substr(shaded.rfind(',') + 1)), 0.0) << shaded;
    // The printed table names every method.
    EXPECT_NE(r.out.find("light field glossy"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("rectified (footprint level)"), std::string::npos) << r.out;
}

TEST(SandboxGlossy, ABadRoughnessIsAUsageErrorNamingTheFlagAndLeavesNoFolder) {
    TempDir dir("glossy-bad");
    for (const std::string& value :
         {std::string("1.5"), std::string("x"), std::string("0,,0.2"), std::string("-0.1")}) {
        const fs::path out = dir.path / "out";
        const ToolRun r =
            glossy(shellQuote(kRoom.string()) + " --roughness " + shellQuote(value) +
                   " --size 32x24 --face-res 8 --samples 1 --out " + shellQuote(out.string()));
        EXPECT_EQ(r.status, 2) << value << ": " << r.err;
        EXPECT_NE(r.err.find("--roughness"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << value;
    }
}

TEST(SandboxGlossy, HelpNamesEveryMethodAndPointsToBenchForTiming) {
    const ToolRun r = glossy("--help");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* m : {"envmap+chain", "boxproj+chain", "rectified (roughness level)",
                          "rectified (footprint level)", "layered (footprint level)",
                          "light field glossy", "bench"})
        EXPECT_NE(r.out.find(m), std::string::npos) << m;
}

} // namespace
