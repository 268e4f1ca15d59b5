// Bad input to specula-cook (docs/design.md §8): every argument of every subcommand malformed,
// missing files, truncated and wrong-type inputs. Each must give exactly one error line that
// names the flag or file, a non-zero exit, nothing on stdout, and leave the output folder
// (a previously cooked probe) byte-for-byte as it was. Interrupted bakes (SIGINT, SIGTERM)
// must leave the previous cooked asset intact and no temporary files behind.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace fs = std::filesystem;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kScenes = SPECULA_TEST_SCENES;
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets" / "room" / "room.gltf";

struct CookRun {
    int status = -1; // exit code, or 128 + signal
    std::string out, err;
};

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Runs specula-cook with `args` (no shell: each argument passed as is).
CookRun cook(const std::vector<std::string>& args, const fs::path& scratch, double signalAfter = -1,
             int sig = SIGINT) {
    const fs::path outFile = scratch / "stdout.txt", errFile = scratch / "stderr.txt";
    std::vector<std::string> argv = {kCook.string()};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (auto& a : argv)
        cargv.push_back(a.data());
    cargv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, outFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = -1;
    CookRun r;
    if (posix_spawn(&pid, kCook.c_str(), &fa, nullptr, cargv.data(), environ) != 0) return r;
    posix_spawn_file_actions_destroy(&fa);
    if (signalAfter >= 0) {
        std::this_thread::sleep_for(std::chrono::duration<double>(signalAfter));
        ::kill(pid, sig);
    }
    int st = 0;
    ::waitpid(pid, &st, 0);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : (WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1);
    r.out = slurp(outFile);
    r.err = slurp(errFile);
    return r;
}

// Every file below `dir` (relative path -> bytes), and what else sits beside `dir`.
using Snapshot = std::map<std::string, std::string>;
Snapshot snapshot(const fs::path& dir) {
    Snapshot s;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        s[fs::relative(e.path(), dir).string()] = e.is_regular_file() ? slurp(e.path()) : "<dir>";
    for (const auto& e : fs::directory_iterator(dir.parent_path()))
        s["../" + e.path().filename().string()] = "<entry>";
    return s;
}

std::vector<std::string> errorLines(const std::string& err) {
    std::vector<std::string> lines;
    std::size_t start = 0;
    while (start < err.size()) {
        const std::size_t nl = err.find('\n', start);
        const std::string line = err.substr(start, nl == std::string::npos ? nl : nl - start);
        if (line.find("error:") != std::string::npos) lines.push_back(line);
        if (nl == std::string::npos) break;
        start = nl + 1;
    }
    return lines;
}

class BadInput : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        root_ = fs::temp_directory_path() / ("specula-bad-input-" + std::to_string(::getpid()));
        fs::create_directories(root_ / "work");
        fs::create_directories(root_ / "scratch");
        // A previously cooked probe that every failing run must leave alone.
        const CookRun r = cook({"bake", kRoom.string(), "--out",
                                (root_ / "work" / "probe").string(), "--face-res", "8"},
                               root_ / "scratch");
        ASSERT_EQ(r.status, 0) << r.err;
        // Inputs of every kind of wrong.
        std::ofstream(root_ / "notgltf.glb") << "this is not a glTF file at all";
        std::ofstream(root_ / "empty.gltf");
        const std::string glb = slurp(kScenes / "box/Box.glb");
        std::ofstream(root_ / "truncated.glb", std::ios::binary) << glb.substr(0, glb.size() / 2);
        std::ofstream(root_ / "wrongtypes.gltf") << R"({"asset": 5, "scenes": "x", "nodes": {}})";
        std::ofstream(root_ / "version3.gltf")
            << R"({"asset": {"version": "3.0"}, "scenes": [{"nodes": []}], "scene": 0})";
        std::ofstream(root_ / "hugecount.gltf")
            << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4000000000000}],)"
               R"( "scenes": [{"nodes": []}], "scene": 0})";
        std::ofstream(root_ / "notimage.exr") << "not an EXR";
        const std::string exr = slurp(root_ / "work" / "probe" / "layer_00.ktx2");
        std::ofstream(root_ / "truncated.exr", std::ios::binary) << exr.substr(0, exr.size() / 3);
        std::ofstream(root_ / "truncated.ktx2", std::ios::binary) << exr.substr(0, exr.size() / 3);
        std::ofstream(root_ / "afile") << "x";
        before_ = snapshot(root_ / "work" / "probe");
    }
    static void TearDownTestSuite() { fs::remove_all(root_); }

    // Runs, then checks the common contract and that the line mentions `mustName`.
    static void expectRefused(const std::vector<std::string>& args, const std::string& mustName,
                              int status) {
        std::string shown;
        for (const auto& a : args)
            shown += a + " ";
        const CookRun r = cook(args, root_ / "scratch");
        EXPECT_EQ(r.status, status) << shown << "\n" << r.err;
        EXPECT_TRUE(r.out.empty()) << shown << "\n" << r.out;
        const auto lines = errorLines(r.err);
        ASSERT_EQ(lines.size(), 1u) << shown << "\n" << r.err;
        EXPECT_NE(lines[0].find(mustName), std::string::npos)
            << shown << "\nthe error must name '" << mustName << "': " << lines[0];
        EXPECT_EQ(snapshot(root_ / "work" / "probe"), before_) << shown << " changed the output";
        std::printf("[bad-input] exit %d  %-60s -> %s\n", r.status, shown.c_str(),
                    lines[0].c_str());
    }

    static fs::path root_;
    static Snapshot before_;
};
fs::path BadInput::root_;
Snapshot BadInput::before_;

std::string p(const fs::path& x) {
    return x.string();
}

} // namespace

TEST_F(BadInput, ToolLevelArguments) {
    expectRefused({}, "missing subcommand", 2);
    expectRefused({"frobnicate"}, "frobnicate", 2);
    expectRefused({"--frobnicate"}, "--frobnicate", 2);
    expectRefused({""}, "unknown subcommand", 2);
}

TEST_F(BadInput, InspectArguments) {
    expectRefused({"inspect"}, "FILE", 2);
    expectRefused({"inspect", "a.glb", "b.glb"}, "FILE", 2);
    expectRefused({"inspect", "--frobnicate", p(kScenes / "box/Box.glb")}, "--frobnicate", 2);
    expectRefused({"inspect", p(root_ / "missing.glb")}, "missing.glb", 1);
    expectRefused({"inspect", p(root_ / "notgltf.glb")}, "notgltf.glb", 1);
    expectRefused({"inspect", p(root_ / "empty.gltf")}, "empty.gltf", 1);
    expectRefused({"inspect", p(root_ / "truncated.glb")}, "truncated.glb", 1);
    expectRefused({"inspect", p(root_ / "wrongtypes.gltf")}, "wrongtypes.gltf", 1);
    expectRefused({"inspect", p(root_ / "version3.gltf")}, "version3.gltf", 1);
    expectRefused({"inspect", p(root_ / "hugecount.gltf")}, "hugecount.gltf", 1);
    // A folder is inspected as cooked textures: one without any is refused, naming it, and so
    // is a damaged texture.
    fs::create_directories(root_ / "no-textures");
    expectRefused({"inspect", p(root_ / "no-textures")}, "no-textures", 1);
    expectRefused({"inspect", p(root_ / "truncated.ktx2")}, "truncated.ktx2", 1);
    expectRefused({"inspect", p(kScenes / "box/Box.glb"), "--dump-exr", p(root_ / "dump")},
                  "--dump-exr", 2);
}

TEST_F(BadInput, BakeArguments) {
    const std::string out = p(root_ / "work" / "probe");
    const std::string scene = p(kRoom);
    expectRefused({"bake"}, "SCENE", 2);
    expectRefused({"bake", scene}, "--out", 2);
    expectRefused({"bake", scene, "--out"}, "--out", 2);
    expectRefused({"bake", scene, "--out", ""}, "--out", 2);
    expectRefused({"bake", scene, scene, "--out", out}, "SCENE", 2);
    expectRefused({"bake", scene, "--out", out, "--frobnicate"}, "--frobnicate", 2);
    for (const char* v : {"abc", "0", "-3", "4097", "1.5", "", "99999999999999999999", "8x"})
        expectRefused({"bake", scene, "--out", out, "--face-res", v}, "--face-res", 2);
    expectRefused({"bake", scene, "--out", out, "--face-res"}, "--face-res", 2);
    for (const char* v : {"1,2", "a,b,c", "1,2,3,4", "nan,0,0", "inf,0,0", "1e30,0,0", "", ",,"})
        expectRefused({"bake", scene, "--out", out, "--probe", v}, "--probe", 2);
    expectRefused({"bake", scene, "--out", out, "--flavour", "frobnicate"}, "--flavour", 2);
    expectRefused({"bake", scene, "--out", out, "--layers", "frobnicate"}, "--layers", 2);
    // Files: missing, wrong kind, truncated.
    expectRefused({"bake", p(root_ / "missing.gltf"), "--out", out}, "missing.gltf", 1);
    expectRefused({"bake", p(root_ / "truncated.glb"), "--out", out}, "truncated.glb", 1);
    expectRefused({"bake", p(root_ / "wrongtypes.gltf"), "--out", out}, "wrongtypes.gltf", 1);
    expectRefused({"bake", scene, "--out", out, "--sky", p(root_ / "missing.exr")}, "missing.exr",
                  1);
    expectRefused({"bake", scene, "--out", out, "--sky", p(root_ / "notimage.exr")}, "notimage.exr",
                  1);
    expectRefused({"bake", scene, "--out", out, "--sky", p(root_ / "truncated.exr")},
                  "truncated.exr", 1);
    // An output that cannot be a probe folder: under a regular file, or a regular file.
    expectRefused({"bake", scene, "--face-res", "4", "--out", p(root_ / "afile" / "sub")}, "afile",
                  1);
    expectRefused({"bake", scene, "--face-res", "4", "--out", p(root_ / "afile")}, "afile", 1);
    EXPECT_EQ(slurp(root_ / "afile"), "x") << "a file given as --out must not be replaced";
    // An existing folder that is not a cooked probe is never replaced.
    fs::create_directories(root_ / "precious");
    std::ofstream(root_ / "precious" / "notes.txt") << "keep me";
    expectRefused({"bake", scene, "--face-res", "4", "--out", p(root_ / "precious")}, "precious",
                  1);
    EXPECT_EQ(slurp(root_ / "precious" / "notes.txt"), "keep me");
}

TEST_F(BadInput, PlanArguments) {
    const std::string scene = p(kRoom);
    expectRefused({"plan"}, "SCENE", 2);
    expectRefused({"plan", scene, "--frobnicate"}, "--frobnicate", 2);
    for (const char* v : {"abc", "0", "-1", "90", "nan"})
        expectRefused({"plan", scene, "--max-error-deg", v}, "--max-error-deg", 2);
    expectRefused({"plan", scene, "--probe", "1,2"}, "--probe", 2);
    expectRefused({"plan", p(root_ / "missing.gltf")}, "missing.gltf", 1);
}

TEST_F(BadInput, InterruptedBakeLeavesThePreviousAssetAndNoTemporaries) {
    const fs::path out = root_ / "work" / "probe";
    // Signals at several moments: during the scene load (default action) and during the
    // bake (the cooker's guard stops at the next row). 2048^2 faces take far longer than
    // the latest signal on any machine this runs on.
    for (int sig : {SIGINT, SIGTERM})
        for (double after : {0.05, 0.8, 2.5}) {
            const auto t0 = std::chrono::steady_clock::now();
            const CookRun r = cook({"bake", p(kRoom), "--out", p(out), "--face-res", "2048"},
                                   root_ / "scratch", after, sig);
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            std::printf("[bad-input] %s after %.2f s: exit %d in %.2f s, stderr: %s",
                        sig == SIGINT ? "SIGINT" : "SIGTERM", after, r.status, s,
                        r.err.empty() ? "(empty)\n" : r.err.c_str());
            EXPECT_NE(r.status, 0);
            EXPECT_LE(errorLines(r.err).size(), 1u) << r.err;
            EXPECT_EQ(snapshot(out), before_) << "the previous cooked probe must stay intact";
            for (const auto& e : fs::directory_iterator(out.parent_path())) {
                const std::string name = e.path().filename().string();
                EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name << " left behind";
                EXPECT_EQ(name.find(".old-"), std::string::npos) << name << " left behind";
            }
        }
}
