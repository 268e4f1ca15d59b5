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

// A copy of `original`'s folder in `dir` with every material black. For the two rooms under
// no sky: the truth and every lookup are black on every reflector pixel, so no frame
// measures anything (ImageStats::hasPsnr).
fs::path blackScene(const fs::path& dir, const fs::path& original = kTwoRooms) {
    fs::copy(original.parent_path(), dir);
    const fs::path scene = dir / original.filename();
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
    const fs::path out = dir.path / "out", scene = blackScene(dir.path / "scene");
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
    const fs::path out = dir.path / "out", scene = blackScene(dir.path / "scene");
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

// A level walked against another scene than it was baked from (issue 34): the probes'
// recorded geometry checksums differ from the scene's, so the walk refuses, naming the field,
// unless --allow-stale, which walks with a warning per probe.
TEST(SandboxInput, ALevelBakedFromAnotherSceneIsRefusedUnlessAllowStale) {
    TempDir dir("level-stale");
    const fs::path baked = dir.path / "level";
    const ToolRun cook =
        runShellTool(kCook, "bake " + shellQuote(kTwoRooms.string()) + " --face-res 8 --out " +
                                shellQuote(baked.string()));
    ASSERT_EQ(cook.status, 0) << cook.err;
    const fs::path other = blackScene(dir.path / "scene");
    const std::string walk = " --level " + shellQuote(baked.string()) +
                             " --path '-3,1.2,0;-1,1.2,0' --frames 2 --size 32x24 --no-timing";
    const fs::path refusedOut = dir.path / "refused";
    const ToolRun refused =
        level(shellQuote(other.string()) + walk + " --out " + shellQuote(refusedOut.string()));
    EXPECT_EQ(refused.status, 1) << refused.err;
    const std::string index = (baked / "level.json").string();
    EXPECT_NE(refused.out.find("error: " + index + ": probes[0].inputs.geometry: "),
              std::string::npos)
        << refused.out;
    EXPECT_NE(refused.err.find("--allow-stale"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(refusedOut / "frames.csv"));

    const ToolRun allowed = level(shellQuote(other.string()) + walk + " --allow-stale --out " +
                                  shellQuote((dir.path / "allowed").string()));
    EXPECT_EQ(allowed.status, 0) << allowed.err;
    EXPECT_NE(allowed.out.find("warning: " + index + ": probes[1].inputs.geometry: "),
              std::string::npos)
        << allowed.out;

    // The scene it was baked from under another sky than the level's (none): the sky is named.
    const ToolRun sky = level(shellQuote(kTwoRooms.string()) + walk + " --sky " +
                              shellQuote(SPECULA_SOURCE_DIR "/assets/scenes/env/field.jpg") +
                              " --out " + shellQuote((dir.path / "sky").string()));
    EXPECT_EQ(sky.status, 1) << sky.err;
    EXPECT_NE(sky.out.find("error: " + index + ": probes[0].inputs.sky: "), std::string::npos)
        << sky.out;
    EXPECT_EQ(sky.out.find("inputs.geometry"), std::string::npos) << sky.out;

    // The scene it was baked from, lit by the level's own sky, walks without a word of
    // staleness.
    const ToolRun same = level(shellQuote(kTwoRooms.string()) + walk + " --out " +
                               shellQuote((dir.path / "same").string()));
    EXPECT_EQ(same.status, 0) << same.err;
    EXPECT_EQ(same.out.find("inputs."), std::string::npos) << same.out;
}

// Probes of one level at two face sizes: one cube-map array cannot hold them, and the twin
// (which the walk measures with) refuses them as the GPU level does, naming the probe.
TEST(SandboxInput, ALevelMixingFaceSizesIsRefusedNamingTheProbe) {
    TempDir dir("level-mixed");
    const fs::path small = dir.path / "small", large = dir.path / "large";
    for (const auto& [folder, res] : {std::pair{small, "8"}, std::pair{large, "16"}}) {
        const ToolRun cook =
            runShellTool(kCook, "bake " + shellQuote(kTwoRooms.string()) + " --face-res " + res +
                                    " --out " + shellQuote(folder.string()));
        ASSERT_EQ(cook.status, 0) << cook.err;
    }
    const nlohmann::json index = nlohmann::json::parse(std::ifstream(small / "level.json"));
    ASSERT_GE(index["probes"].size(), 2u);
    const std::string second = index["probes"][1]["folder"];
    fs::remove_all(small / second);
    fs::copy(large / second, small / second);
    const ToolRun r =
        level(shellQuote(kTwoRooms.string()) + " --level " + shellQuote(small.string()) +
              " --path '-3,1.2,0;-1,1.2,0' --frames 2 --size 32x24 --no-timing " + "--out " +
              shellQuote((dir.path / "out").string()));
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find((small / "level.json").string() + ": probes[1]: face resolution 16 "
                                                           "differs from the level's 8"),
              std::string::npos)
        << r.err;
}

// A probe cooked on its own records its inputs too (format 2.2): walked against another scene
// (the room with its materials black) it is refused naming "inputs.geometry", unless
// --allow-stale; against the scene it was baked from, not a word. Under another --sky than the
// bake's (none), "inputs.sky".
TEST(SandboxInput, AProbeBakedFromAnotherSceneIsRefusedUnlessAllowStale) {
    TempDir dir("probe-stale");
    const fs::path room = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";
    const fs::path baked = dir.path / "probe";
    const ToolRun cook =
        runShellTool(kCook, "bake " + shellQuote(room.string()) + " --face-res 8 --out " +
                                shellQuote(baked.string()));
    ASSERT_EQ(cook.status, 0) << cook.err;
    const std::string manifest = (baked / "manifest.json").string();
    const nlohmann::json m = nlohmann::json::parse(std::ifstream(manifest));
    ASSERT_TRUE(m.contains("inputs")) << m.dump();
    EXPECT_EQ(m["inputs"]["sky"], "none");
    const fs::path other = blackScene(dir.path / "scene", room);
    const ToolSubcommand walk{kSandbox, "walk"};
    const std::string args =
        shellQuote(manifest) + " --headless --frames 1 --size 32x24 --method bisection";
    const ToolRun refused = walk(args + " --scene " + shellQuote(other.string()) + " --out " +
                                 shellQuote((dir.path / "refused").string()));
    EXPECT_EQ(refused.status, 1) << refused.err;
    EXPECT_NE(refused.out.find("error: " + manifest + ": inputs.geometry: "), std::string::npos)
        << refused.out;
    EXPECT_NE(refused.err.find("--allow-stale"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir.path / "refused" / "frames.csv"));

    const ToolRun allowed =
        walk(args + " --scene " + shellQuote(other.string()) + " --allow-stale --out " +
             shellQuote((dir.path / "allowed").string()));
    EXPECT_EQ(allowed.status, 0) << allowed.err;
    EXPECT_NE(allowed.out.find("warning: " + manifest + ": inputs.geometry: "), std::string::npos)
        << allowed.out;

    const ToolRun sky =
        walk(args + " --sky " + shellQuote(SPECULA_SOURCE_DIR "/assets/scenes/env/field.jpg") +
             " --out " + shellQuote((dir.path / "sky").string()));
    EXPECT_EQ(sky.status, 1) << sky.err;
    EXPECT_NE(sky.out.find("error: " + manifest + ": inputs.sky: "), std::string::npos) << sky.out;
    EXPECT_EQ(sky.out.find("inputs.geometry"), std::string::npos) << sky.out;

    const ToolRun same = walk(args + " --out " + shellQuote((dir.path / "same").string()));
    EXPECT_EQ(same.status, 0) << same.err;
    EXPECT_EQ(same.out.find("inputs."), std::string::npos) << same.out;
}
