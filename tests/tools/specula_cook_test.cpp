// Drives the specula-cook executable the way a user or a script does: through the shell.
#include "support/shell_tool.h"

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

using CookRun = specula::test::ToolRun;
using specula::test::shellQuote;

CookRun cook(const std::string& args) {
    return specula::test::runShellTool(kCook, args);
}

using specula::test::lineCount;

} // namespace

TEST(SpeculaCook, InspectBoxGlbPrintsOneJsonObject) {
    ASSERT_TRUE(fs::exists(kCook)) << kCook;
    const CookRun r = cook("inspect " + shellQuote((kScenes / "box/Box.glb").string()));
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
    const CookRun r = cook("inspect " + shellQuote((kScenes / "box/Box_Draco.glb").string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["triangles"], 12);
    EXPECT_EQ(j["extensionsUsed"], nlohmann::json::array({"KHR_draco_mesh_compression"}));
}

TEST(SpeculaCook, BadFileFailsWithOneLineNamingIt) {
    const fs::path bad =
        fs::temp_directory_path() / ("specula_cook_bad_" + std::to_string(::getpid()) + ".glb");
    std::ofstream(bad) << "this is not a glTF file at all";
    const CookRun r = cook("inspect " + shellQuote(bad.string()));
    fs::remove(bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(bad.filename().string()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("bad magic"), std::string::npos) << r.err;
}

TEST(SpeculaCook, MissingFileFailsWithExitOne) {
    const CookRun r = cook("inspect /nonexistent/specula/missing.gltf");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
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
