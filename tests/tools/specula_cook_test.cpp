// Drives the specula-cook executable the way a user or a script does: through the shell.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kScenes = SPECULA_TEST_SCENES;

struct CookRun {
    int status = -1;
    std::string out, err;
};

std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s)
        q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

CookRun cook(const std::string& args) {
    const fs::path errFile =
        fs::temp_directory_path() / ("specula_cook_test_" + std::to_string(::getpid()) + ".err");
    CookRun r;
    const std::string cmd = quote(kCook.string()) + " " + args + " 2>" + quote(errFile.string());
    FILE* pipe = ::popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0)
        r.out.append(buf, n);
    const int st = ::pclose(pipe);
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    std::ifstream in(errFile);
    r.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    fs::remove(errFile);
    return r;
}

std::size_t lines(const std::string& s) {
    std::size_t n = 0;
    for (char c : s)
        n += c == '\n';
    return n;
}

} // namespace

TEST(SpeculaCook, InspectBoxGlbPrintsOneJsonObject) {
    ASSERT_TRUE(fs::exists(kCook)) << kCook;
    const CookRun r = cook("inspect " + quote((kScenes / "box/Box.glb").string()));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["meshes"], 1);
    EXPECT_EQ(j["primitives"], 1);
    EXPECT_EQ(j["vertices"], 24);
    EXPECT_EQ(j["triangles"], 12);
    EXPECT_EQ(j["nodes"], 2);
    EXPECT_EQ(j["materials"], 1);
    ASSERT_TRUE(j["extensionsUsed"].is_array());
    EXPECT_TRUE(j["extensionsUsed"].empty());
    for (const char* k : {"min", "max"}) {
        ASSERT_TRUE(j["bounds"][k].is_array());
        ASSERT_EQ(j["bounds"][k].size(), 3u);
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(j["bounds"][k][std::size_t(a)].get<double>(), k[1] == 'i' ? -0.5 : 0.5,
                        1e-5);
    }
}

TEST(SpeculaCook, InspectDracoReportsTheExtension) {
    const CookRun r = cook("inspect " + quote((kScenes / "box/Box_Draco.glb").string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["triangles"], 12);
    EXPECT_EQ(j["extensionsUsed"], nlohmann::json::array({"KHR_draco_mesh_compression"}));
}

TEST(SpeculaCook, BadFileFailsWithOneLineNamingIt) {
    const fs::path bad =
        fs::temp_directory_path() / ("specula_cook_bad_" + std::to_string(::getpid()) + ".glb");
    std::ofstream(bad) << "this is not a glTF file at all";
    const CookRun r = cook("inspect " + quote(bad.string()));
    fs::remove(bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(bad.filename().string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bad magic"), std::string::npos) << r.err;
}

TEST(SpeculaCook, MissingFileFailsWithExitOne) {
    const CookRun r = cook("inspect /nonexistent/specula/missing.gltf");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(lines(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("missing.gltf"), std::string::npos) << r.err;
}

TEST(SpeculaCook, UsageErrorsExitTwo) {
    EXPECT_EQ(cook("").status, 2);
    EXPECT_EQ(cook("frobnicate").status, 2);
    EXPECT_EQ(cook("--frobnicate").status, 2);
    EXPECT_EQ(cook("inspect --frobnicate x.glb").status, 2);
    EXPECT_EQ(cook("inspect").status, 2);
    EXPECT_EQ(cook("inspect a.glb b.glb").status, 2);
    const CookRun r = cook("frobnicate");
    EXPECT_NE(r.err.find("unknown subcommand 'frobnicate'"), std::string::npos) << r.err;
}

TEST(SpeculaCook, HelpForToolAndSubcommand) {
    for (const char* flag : {"--help", "-h"}) {
        const CookRun r = cook(flag);
        EXPECT_EQ(r.status, 0);
        EXPECT_NE(r.out.find("inspect"), std::string::npos) << r.out;
    }
    const CookRun r = cook("inspect --help");
    EXPECT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("usage: specula-cook inspect"), std::string::npos) << r.out;
}
