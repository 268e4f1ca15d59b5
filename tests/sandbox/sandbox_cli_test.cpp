// Drives the specula-sandbox executable through the shell on small frames: help, command-line
// and input errors, a headless walk, a quick bench (files exist, parse and hold sane figures)
// and the window walk under Xvfb.
#include "engine/image_io/image_io.h"

#include "support/csv_table.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kTool = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

using specula::test::shellQuote;
using specula::test::ToolRun;

ToolRun tool(const std::string& args, const std::string& prefix = "") {
    return specula::test::runShellTool(kTool, args, prefix);
}

// specula-sandbox walk on the default room, headless, writing into `out`.
ToolRun headlessRoomWalk(const std::string& flags, const fs::path& out) {
    return tool("walk " + shellQuote(kRoom.string()) + " --headless " + flags + " --out " +
                shellQuote(out.string()));
}

struct TempDir : specula::test::TempDir {
    explicit TempDir(const std::string& name) : specula::test::TempDir("sandbox-" + name) {}
};

using Table = specula::test::CsvTable;
using specula::test::lineCount;
using specula::test::num;
using specula::test::readCsv;

} // namespace

TEST(SpeculaSandbox, HelpForToolAndEachSubcommand) {
    ASSERT_TRUE(fs::exists(kTool)) << kTool;
    for (const char* args : {"--help", "walk --help", "bench --help", "bench -h"}) {
        const ToolRun r = tool(args);
        EXPECT_EQ(r.status, 0) << args << ": " << r.err;
        EXPECT_NE(r.out.find("usage: specula-sandbox"), std::string::npos) << args;
        EXPECT_TRUE(r.err.empty()) << args << ": " << r.err;
    }
    EXPECT_NE(tool("--help").out.find("bench"), std::string::npos);
    EXPECT_NE(tool("walk --help").out.find("--headless"), std::string::npos);
    EXPECT_NE(tool("bench --help").out.find("--quick"), std::string::npos);
}

TEST(SpeculaSandbox, CommandLineErrorsExitTwo) {
    const std::string room = shellQuote(kRoom.string());
    for (const std::string& args : std::vector<std::string>{
             std::string(""), std::string("nonsense"), std::string("--bogus"), std::string("walk"),
             "walk " + room + " " + room, "walk " + room + " --method nope",
             "walk " + room + " --frames 0 --headless", "walk " + room + " --path spiral",
             "walk " + room + " --de -1", "walk " + room + " --size 10",
             "walk " + room + " --compare", "walk " + room + " --frames", "bench --bogus",
             "bench stray", std::string("bench --max-frames 1"),
             "walk " + room + " --roughness 1.5", "walk " + room + " --roughness nan",
             "walk " + room + " --samples 0"}) {
        const ToolRun r = tool(args);
        EXPECT_EQ(r.status, 2) << "'" << args << "': " << r.err;
        EXPECT_NE(r.err.find("error"), std::string::npos) << args;
        EXPECT_TRUE(r.out.empty()) << args;
    }
}

TEST(SpeculaSandbox, BadInputExitsOneWithOneLineNamingTheFile) {
    TempDir dir("bad");
    const fs::path missing = dir.path / "missing.gltf";
    const fs::path garbage = dir.path / "garbage.gltf";
    std::ofstream(garbage) << "{ not json";
    const fs::path manifest = dir.path / "manifest.json";
    std::ofstream(manifest) << "{\"format\": \"specula-probe\", \"version\": 999}";
    const fs::path text = dir.path / "notes.txt";
    std::ofstream(text) << "hello";
    for (const fs::path& f : {missing, garbage, manifest, text}) {
        const ToolRun r = tool("walk " + shellQuote(f.string()) + " --headless --frames 1 --out " +
                               shellQuote((dir.path / "out").string()));
        EXPECT_EQ(r.status, 1) << f << ": " << r.err;
        EXPECT_EQ(lineCount(r.err), 1u) << r.err;
        EXPECT_NE(r.err.find(f.string()), std::string::npos) << r.err;
    }
    const ToolRun b = tool("bench --quick --scene " + shellQuote(missing.string()) + " --out " +
                           shellQuote((dir.path / "bench").string()));
    EXPECT_EQ(b.status, 1) << b.err;
    EXPECT_EQ(lineCount(b.err), 1u) << b.err;
    EXPECT_NE(b.err.find(missing.string()), std::string::npos) << b.err;
}

TEST(SpeculaSandbox, HeadlessWalkWritesFramesSheetAndCsvThenReplaysItsManifest) {
    TempDir dir("walk");
    const fs::path out = dir.path / "walk";
    const ToolRun r =
        headlessRoomWalk("--frames 3 --size 96x72 --face-res 32 --path figure8 --compare", out);
    ASSERT_EQ(r.status, 0) << r.err;
    for (int i = 0; i < 3; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.png", i);
        ASSERT_TRUE(fs::exists(out / name)) << name;
        const specula::Image img = specula::readImage((out / name).string());
        EXPECT_EQ(img.width, 96);
        EXPECT_EQ(img.height, 72);
    }
    EXPECT_FALSE(fs::exists(out / "frame_0003.png"));
    const specula::Image sheet = specula::readImage((out / "contact_sheet.png").string());
    EXPECT_GT(sheet.width, 96);

    const Table rows = readCsv(out / "frames.csv");
    ASSERT_EQ(rows.size(), 3u);
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_EQ(num(rows[i], "frame"), double(i));
        const double ms = num(rows[i], "pass_ms");
        EXPECT_TRUE(std::isfinite(ms) && ms > 0) << ms;
        // The sphere (first reflector) is authored at (-0.42, 1.2, 0); the path keeps it within
        // its slack in the 2 m cell (0.26 m) of there.
        EXPECT_NEAR(num(rows[i], "reflector_x"), -0.42, 0.27);
        EXPECT_NEAR(num(rows[i], "reflector_y"), 1.2, 0.27);
        EXPECT_NEAR(num(rows[i], "reflector_z"), 0.0, 0.27);
        const double psnr = num(rows[i], "psnr");
        EXPECT_TRUE(std::isfinite(psnr) && psnr > 12.0) << psnr; // bisection against Embree
    }

    // The baked probe replays from its manifest (scene from its "source").
    const fs::path manifest = out / "probe" / "manifest.json";
    ASSERT_TRUE(fs::exists(manifest));
    const fs::path again = dir.path / "again";
    const ToolRun m = tool("walk " + shellQuote(manifest.string()) +
                           " --headless --frames 1 --size 96x72 --method envmap "
                           "--out " +
                           shellQuote(again.string()));
    ASSERT_EQ(m.status, 0) << m.err;
    EXPECT_EQ(readCsv(again / "frames.csv").size(), 1u);
}

// --roughness draws every reflector rough and compares against the GGX truth (the truth
// following the drawn roughness is ReflectionSceneTruth's test). Measured at 160x120, secant:
// 30.8 / 32.2 dB on the first two frames with 256 samples.
TEST(SpeculaSandbox, HeadlessWalkWithRoughnessComparesAgainstTheGgxTruth) {
    TempDir dir("rough-walk");
    const fs::path out = dir.path / "walk";
    const ToolRun r = headlessRoomWalk(
        "--frames 2 --size 96x72 --face-res 32 --method secant --compare --roughness 0.2 "
        "--samples 32",
        out);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("every reflector at roughness 0.2 (GGX truth, 32 samples a pixel)"),
              std::string::npos)
        << r.out;
    const Table rows = readCsv(out / "frames.csv");
    ASSERT_EQ(rows.size(), 2u);
    for (const auto& row : rows) {
        const double psnr = num(row, "psnr");
        EXPECT_TRUE(std::isfinite(psnr) && psnr > 20.0) << psnr;
    }
}

// The third flavour: walk bakes a PEM from the scene (8 viewpoints on the walk's camera
// orbit, inferred for the walk's own frame size) and sets its parameter to the frame's t,
// the reflectors staying where the maps were inferred; its manifest replays with the PEM.
// Both frames (t = 0 and 1/2) are baked viewpoints: there the PEM must reproduce the full
// multi-bounce truth (self- and inter-reflections included), which no single-bounce probe
// can (the room's layered distance probe reaches about 23 dB full).
TEST(SpeculaSandbox, HeadlessPemWalkBakesAndFollowsTheOrbit) {
    TempDir dir("pem-walk");
    const fs::path out = dir.path / "walk";
    const std::string flags = "--method pem --frames 2 --size 96x72 --path line --compare";
    const ToolRun r = headlessRoomWalk(flags, out);
    ASSERT_EQ(r.status, 0) << r.err;
    const Table rows = readCsv(out / "frames.csv");
    for (const char* frame : {"frame_0000.png", "frame_0001.png"})
        EXPECT_TRUE(fs::exists(out / frame)) << frame;
    ASSERT_EQ(rows.size(), 2u);
    for (const auto& row : rows) {
        const double psnr = num(row, "psnr"), full = num(row, "psnr_full");
        std::printf("[pem walk] frame %s (a baked viewpoint): PSNR env %.2f dB, full %.2f dB\n",
                    row.at("frame").c_str(), psnr, full);
        EXPECT_TRUE(std::isfinite(psnr) && psnr > 8.0) << psnr;
        EXPECT_GE(full, 35.0) << "on the manifold against the multi-bounce truth";
        // The sphere stays where the scene authors it (-0.42, 1.2, 0).
        EXPECT_NEAR(num(row, "reflector_x"), -0.42, 1e-4);
        EXPECT_NEAR(num(row, "reflector_z"), 0.0, 1e-4);
    }
    const ToolRun m = tool("walk " + shellQuote((out / "probe" / "manifest.json").string()) +
                           " --headless --frames 1 --size 96x72 --out " +
                           shellQuote((dir.path / "again").string()));
    ASSERT_EQ(m.status, 0) << m.err;
    EXPECT_NE(m.out.find("(pem,"), std::string::npos) << m.out; // not the default bisection
    EXPECT_EQ(readCsv(dir.path / "again" / "frames.csv").size(), 1u);
}

// A PEM cooked along the scene camera's animation (--path camera: the room whose camera
// dollies, scripts/make_room_camera_path.py) walks that path, first key to last: frames 0,
// 2 and 4 of five are its three samples (t = 0, 1/2, 1), on the manifold; 1 and 3 half-way.
// Cooked under the cooker's default black sky: the walk compares against that sky (the
// manifest's "sky_source": ""), not the sandbox's default panorama.
TEST(SpeculaSandbox, HeadlessPemWalkFollowsTheCameraPathItWasBakedAlong) {
    TempDir dir("pem-camera-walk");
    const fs::path scene = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room_camera_path.gltf";
    const fs::path probe = dir.path / "probe";
    const ToolRun cook = specula::test::runShellTool(
        fs::path(SPECULA_BIN_DIR) / "specula-cook",
        "bake " + shellQuote(scene.string()) +
            " --flavour pem --path camera --samples 3 --face-res 32 --image-size 96x72 "
            "--local-layer off --out " +
            shellQuote(probe.string()));
    ASSERT_EQ(cook.status, 0) << cook.err;
    const fs::path out = dir.path / "walk";
    const ToolRun r =
        tool("walk " + shellQuote((probe / "manifest.json").string()) +
             " --headless --frames 5 --size 96x72 --compare --out " + shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("(pem, camera path)"), std::string::npos) << r.out;
    const Table rows = readCsv(out / "frames.csv");
    ASSERT_EQ(rows.size(), 5u);
    double previousAngle = -1e9;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double full = num(rows[i], "psnr_full"), angle = num(rows[i], "camera_angle_deg");
        std::printf("[pem camera walk] frame %zu: camera %.1f deg, full %.2f dB\n", i, angle, full);
        // The dolly turns the eye about the probe one way, about 38 degrees in all.
        EXPECT_GT(angle, previousAngle);
        previousAngle = angle;
        if (i % 2 == 0) {
            EXPECT_GE(full, 35.0) << "frame " << i << " is a sample's own view";
        } else {
            EXPECT_LT(full, std::min(num(rows[i - 1], "psnr_full"), num(rows[i + 1], "psnr_full")))
                << "frame " << i << " lies half-way between two samples";
        }
    }
    EXPECT_NEAR(previousAngle, 38.05, 0.5);

    // Any method walks the same path (--path camera): the same cameras, reflectors still.
    const ToolRun secant = tool("walk " + shellQuote(scene.string()) +
                                " --path camera --method secant --headless --frames 5 --size "
                                "96x72 --face-res 32 --out " +
                                shellQuote((dir.path / "secant").string()));
    ASSERT_EQ(secant.status, 0) << secant.err;
    const Table secantRows = readCsv(dir.path / "secant" / "frames.csv");
    ASSERT_EQ(secantRows.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        EXPECT_NEAR(num(secantRows[i], "camera_angle_deg"), num(rows[i], "camera_angle_deg"), 1e-3);
        EXPECT_NEAR(num(secantRows[i], "reflector_x"), -0.42, 1e-4);
    }
    // A still camera has no path; a reflector parameter walks the reflectors, not the camera.
    const ToolRun still =
        headlessRoomWalk("--path camera --frames 1 --size 64x48", dir.path / "still");
    EXPECT_EQ(still.status, 1);
    EXPECT_NE(still.err.find("nothing animates it"), std::string::npos) << still.err;
    EXPECT_FALSE(fs::exists(dir.path / "still"));
    const ToolRun mixed =
        headlessRoomWalk("--path camera --parameter reflector --method pem", dir.path / "mixed");
    EXPECT_EQ(mixed.status, 2);
    EXPECT_NE(mixed.err.find("--path"), std::string::npos) << mixed.err;

    // The bench bakes its PEM rows along the animation of a scene whose camera moves.
    const fs::path bench = dir.path / "bench";
    const ToolRun b =
        tool("bench --quick --size 96x72 --face-res 32 --max-frames 4 --scene " +
             shellQuote(scene.string()) + " --pem-samples 3 --out " + shellQuote(bench.string()));
    ASSERT_EQ(b.status, 0) << b.err;
    const std::string log = b.out + b.err;
    EXPECT_NE(log.find("3 viewpoints on the camera path"), std::string::npos) << log;
    std::map<std::string, double> full;
    for (const auto& row : readCsv(bench / "bench.csv"))
        if (row.at("method") == "pem" || row.at("params").find("pem-camera") != std::string::npos)
            full[row.at("method") + " " + row.at("params")] = num(row, "psnr_full");
    ASSERT_EQ(full.count("pem N=3 t=on"), 1u);
    ASSERT_EQ(full.count("pem N=3 t=off"), 1u);
    EXPECT_GE(full["pem N=3 t=on"], 35.0);
    EXPECT_LT(full["pem N=3 t=off"], full["pem N=3 t=on"]);
    EXPECT_EQ(full.count("layered d_e=0.01 pem-camera N=3 t=off"), 1u);
}

TEST(SpeculaSandbox, QuickBenchWritesSaneReport) {
    TempDir dir("bench");
    const fs::path out = dir.path / "bench";
    const ToolRun r = tool("bench --quick --size 96x72 --face-res 32 --max-frames 4 --out " +
                           shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const Table rows = readCsv(out / "bench.csv");
    std::map<std::string, int> perScene;
    for (const auto& row : rows) {
        const std::string scene = row.at("scene"), method = row.at("method");
        ++perScene[scene];
        const double ms = num(row, "ms_median"), ratio = num(row, "ratio_to_envmap");
        EXPECT_TRUE(std::isfinite(ms) && ms > 0) << scene << " " << method << " " << ms;
        EXPECT_TRUE(std::isfinite(ratio) && ratio > 0) << scene << " " << method;
        const double psnr = num(row, "psnr"), rmse = num(row, "rmse");
        const double fetches = num(row, "fetches_per_pixel"), bytes = num(row, "gpu_bytes");
        if (method == "groundtruth") {
            EXPECT_TRUE(std::isinf(psnr) || psnr >= 99.0) << psnr;
            EXPECT_EQ(rmse, 0.0);
            continue;
        }
        EXPECT_TRUE(std::isfinite(psnr) && psnr > 5.0 && psnr < 99.0)
            << scene << " " << method << " " << psnr;
        EXPECT_TRUE(std::isfinite(rmse) && rmse > 0.0) << method;
        EXPECT_GT(bytes, 0.0) << method;
        EXPECT_GT(num(row, "bake_s"), 0.0) << method;
        // The whole frame holds the reflector pass (wall clock on llvmpipe; a GPU's pass
        // time is its share of the frame's).
        const double frameMs = num(row, "frame_ms_median");
        const double frameRatio = num(row, "frame_ratio_to_envmap");
        EXPECT_TRUE(std::isfinite(frameMs) && frameMs >= ms)
            << method << " " << frameMs << " " << ms;
        EXPECT_TRUE(std::isfinite(frameRatio) && frameRatio > 0) << scene << " " << method;
        if (method == "envmap" && row.at("params") == "-") { // the float row: every ratio's base
            EXPECT_EQ(frameRatio, 1.0);
            EXPECT_EQ(ratio, 1.0);
            EXPECT_NEAR(fetches, 1.0, 1e-9); // one direction lookup, sky included
        }
        if (method == "bisection" || method == "secant" || method == "march") {
            EXPECT_GT(fetches, 1.5) << method;
        }
    }
    // The PEM rows: the walk orbit's camera at a sample (t=on) and half-way (t=off).
    int pemRows = 0;
    for (const auto& row : rows) {
        if (row.at("method") != "pem") continue;
        ++pemRows;
        const double env = num(row, "psnr"), full = num(row, "psnr_full");
        std::printf("[pem bench] %s %s: PSNR env %.2f dB, full %.2f dB, bake %.2f s\n",
                    row.at("scene").c_str(), row.at("params").c_str(), env, full,
                    num(row, "bake_s"));
        EXPECT_TRUE(std::isfinite(full) && full > 5.0) << row.at("scene") << " " << full;
        // At a baked viewpoint of the room the PEM reproduces the multi-bounce truth (47 dB
        // measured at 160x120); the room's single-bounce methods stay near 23 dB full.
        if (row.at("scene") == "room" && row.at("params").ends_with("t=on")) {
            EXPECT_GE(full, 35.0);
        }
    }
    EXPECT_GE(pemRows, 2); // at least the room's t=on and t=off
    // Beside them the best single-bounce method from the same two cameras.
    int references = 0;
    for (const auto& row : rows)
        if (row.at("params").find("pem-camera") != std::string::npos) {
            ++references;
            std::printf("[pem bench] %s %s %s: PSNR full %.2f dB\n", row.at("scene").c_str(),
                        row.at("method").c_str(), row.at("params").c_str(), num(row, "psnr_full"));
            EXPECT_TRUE(row.at("method") == "layered" || row.at("method") == "bisection");
        }
    EXPECT_GE(references, 2);
    // The format rows: each distance method drawn from the BC6H probe too, in fewer bytes.
    int formatRows = 0;
    for (const auto& row : rows) {
        const std::string& params = row.at("params");
        if (!params.ends_with(" bc6h")) continue;
        ++formatRows;
        for (const auto& twin : rows)
            if (twin.at("scene") == row.at("scene") && twin.at("method") == row.at("method") &&
                twin.at("params") == params.substr(0, params.size() - 5)) {
                EXPECT_LT(num(row, "gpu_bytes"), num(twin, "gpu_bytes")) << params;
            }
    }
    EXPECT_GE(formatRows, 4 * 5);   // at least envmap, boxproj and the three searches a scene
    EXPECT_EQ(perScene.size(), 4u); // room, truck_room, bowl_room, sky_only
    for (const auto& [scene, n] : perScene) {
        EXPECT_GE(n, 10) << scene;
    }
    std::ifstream md(out / "bench.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("renderer: "), std::string::npos);
    EXPECT_NE(text.find("machine: "), std::string::npos);
    EXPECT_NE(text.find("| envmap |"), std::string::npos);
    EXPECT_NE(text.find("| groundtruth |"), std::string::npos);
    // No cell of the table says nan: what was not measured (the truth's frame) says n/a.
    EXPECT_EQ(text.find("| nan |"), std::string::npos);
    EXPECT_NE(text.find("| n/a |"), std::string::npos);
    for (const char* png : {"accuracy_vs_time.png", "strip_room.png", "strip_truck_room.png",
                            "strip_bowl_room.png", "pem_room.png", "pem_bowl_room.png"}) {
        const specula::Image img = specula::readImage((out / png).string());
        EXPECT_GT(img.width, 100) << png;
    }
}

TEST(SpeculaSandbox, WindowWalkRunsUnderXvfb) {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run not installed";
    TempDir dir("window");
    const ToolRun r =
        tool("walk " + shellQuote(kRoom.string()) + " --frames 3 --size 96x72 --face-res 16",
             "xvfb-run -a -s '-screen 0 320x240x24' ");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("3 frames shown"), std::string::npos) << r.out;
}
