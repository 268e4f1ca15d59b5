// specula-sandbox on inputs it used to mishandle (issue 34): a --path @FILE that is a FIFO
// (the walk hung) or a folder (read as no point); a level without probes (the walk crashed);
// and frames that measure nothing, black reflections against a black truth (the means read
// 0.00 dB): such a PSNR prints "none", as every report of the tools has it, and is left out
// of the means.
#include "support/shell_tool.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>

namespace fs = std::filesystem;

namespace {

const fs::path kSandbox = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kTwoRooms = fs::path(SPECULA_SOURCE_DIR) / "assets/two_rooms/two_rooms.gltf";

using namespace specula::test;

const ToolSubcommand level{kSandbox, "level"};
const ToolSubcommand glossy{kSandbox, "glossy"};

// The two rooms with every material black, under no sky: the truth and every lookup are
// black on every reflector pixel, so no frame measures anything (ImageStats::hasPsnr).
fs::path blackTwoRooms(const fs::path& dir) {
    fs::copy(kTwoRooms.parent_path(), dir);
    const fs::path scene = dir / kTwoRooms.filename();
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(scene));
    for (nlohmann::json& m : gltf["materials"])
        m["pbrMetallicRoughness"]["baseColorFactor"] = {0.0, 0.0, 0.0, 1.0};
    std::ofstream(scene) << gltf.dump();
    return scene;
}

} // namespace

TEST(SandboxInput, APathFileMustBeARegularFile) {
    TempDir dir("level-path-kinds");
    const fs::path fifo = dir.path / "path.fifo";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const fs::path& bad : {fifo, dir.path}) {
        const fs::path out = dir.path / "out";
        // Under `timeout`: a walk blocked on the FIFO fails with 124 instead of hanging.
        const ToolRun r =
            runShellTool(kSandbox,
                         "level " + shellQuote(kTwoRooms.string()) + " --path @" +
                             shellQuote(bad.string()) + " --out " + shellQuote(out.string()),
                         "timeout 60 ");
        EXPECT_EQ(r.status, 2) << bad << ": " << r.err;
        EXPECT_NE(r.err.find("error: --path: "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out)) << bad;
    }
}

TEST(SandboxInput, ALevelWithoutProbesIsAnErrorNotACrash) {
    TempDir dir("level-no-probes");
    const fs::path baked = dir.path / "level";
    const ToolRun cook =
        runShellTool(kCook, "bake " + shellQuote(kTwoRooms.string()) + " --face-res 8 --out " +
                                shellQuote(baked.string()));
    ASSERT_EQ(cook.status, 0) << cook.err;
    const fs::path index = baked / "level.json";
    nlohmann::json doc = nlohmann::json::parse(std::ifstream(index));
    doc["probes"] = nlohmann::json::array();
    std::ofstream(index) << doc.dump(2);
    const fs::path out = dir.path / "out";
    const ToolRun r =
        level(shellQuote(kTwoRooms.string()) + " --level " + shellQuote(baked.string()) +
              " --path '-3,1.2,0;-1,1.2,0' " + "--frames 2 --size 32x24 --no-timing --out " +
              shellQuote(out.string()));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(index.string() + ": probes"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

TEST(SandboxInput, ALevelWalkThatMeasuresNothingSaysNone) {
    TempDir dir("level-none");
    const fs::path out = dir.path / "out", scene = blackTwoRooms(dir.path / "scene");
    const ToolRun r = level(shellQuote(scene.string()) + " --sky '' --face-res 8 --frames 2 " +
                            "--size 32x24 --no-timing --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* blend : {"nearest", "engine", "visibility"}) {
        const std::string head = std::string(blend) + std::string(11 - std::strlen(blend), ' ');
        EXPECT_NE(r.out.find(head + " PSNR mean none worst none | overlap frames mean none worst "
                                    "none"),
                  std::string::npos)
            << r.out;
    }
    EXPECT_EQ(r.out.find("PSNR mean 0.00"), std::string::npos) << r.out;
    const std::vector<std::string> frames = fileLines(out / "frames.csv");
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(frames[1].rfind("0,-3,1.2,0,none,none,none,", 0), 0u) << frames[1];
    const std::vector<std::string> summary = fileLines(out / "summary.csv");
    ASSERT_GE(summary.size(), 5u);
    EXPECT_EQ(summary[1].rfind("nearest,none,none,none,none,", 0), 0u) << summary[1];
    EXPECT_EQ(summary[4].rfind("visibility (mirror lookup),none,none,", 0), 0u) << summary[4];
}

TEST(SandboxInput, AGlossyBenchThatMeasuresNothingSaysNone) {
    TempDir dir("glossy-none");
    const fs::path out = dir.path / "out", scene = blackTwoRooms(dir.path / "scene");
    const ToolRun r = glossy(shellQuote(scene.string()) + " --sky '' --roughness 0.3 " +
                             "--size 32x24 --face-res 8 --samples 4 --no-timing --out " +
                             shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const std::vector<std::string> rows = fileLines(out / "glossy.csv");
    ASSERT_EQ(rows.size(), 7u);
    for (std::size_t i = 1; i < rows.size(); ++i)
        EXPECT_NE(rows[i].find("\",none,none,"), std::string::npos) << rows[i];
    EXPECT_NE(r.out.find("truth noise floor none dB"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("| 0.00"), std::string::npos) << r.out;
}
