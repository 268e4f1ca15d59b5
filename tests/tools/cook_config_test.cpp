// specula-cook bake with `--config FILE` (issue 11, item 8) and flags of the other flavour
// (item 7): a level's bake options read from a TOML file beside the scene, a flag on the
// command line overriding the file, a misspelt key or a missing file refused with exit 2
// naming --config, and a flag of one flavour given to the other refused, naming the flag and
// the flavour, before anything is written.
#include "tests/support/child_process.h"
#include "tests/support/scratch_dir_test.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using specula::test::ChildResult;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets" / "room" / "room.gltf";

class CookConfig : public specula::test::ScratchDirTest {
protected:
    CookConfig() : ScratchDirTest("specula-cook-config") {}

    ChildResult cook(std::vector<std::string> args) {
        return specula::test::runChild(kCook, std::move(args), root_ / "scratch");
    }
    fs::path writeConfig(const std::string& name, const std::string& text) {
        const fs::path p = root_ / name;
        std::ofstream(p) << text;
        return p;
    }
    int manifestFaceRes(const fs::path& probe) {
        return nlohmann::json::parse(specula::test::slurpFile(probe / "manifest.json"))
            .at("face_res")
            .get<int>();
    }
    // Exit 2, nothing on stdout, one error line naming every word of `mustName`, no output.
    void expectUsageError(const std::vector<std::string>& args,
                          const std::vector<std::string>& mustName) {
        const ChildResult r = cook(args);
        EXPECT_EQ(r.status, 2) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
        const std::string line = r.err.substr(r.err.find("error:"));
        EXPECT_EQ(line.find('\n'), line.size() - 1) << r.err;
        for (const std::string& word : mustName)
            EXPECT_NE(line.find(word), std::string::npos) << "must name " << word << ": " << line;
        EXPECT_FALSE(fs::exists(root_ / "probe")) << "a refused bake wrote its output";
    }
};

} // namespace

TEST_F(CookConfig, ConfigFileSetsABakeOptionAndTheCommandLineWins) {
    const fs::path level =
        writeConfig("level.toml", "# room's bake options\n[bake]\nface-res = 8\n");
    const ChildResult fromFile =
        cook({"bake", kRoom.string(), "--out", (root_ / "a").string(), "--config", level.string()});
    ASSERT_EQ(fromFile.status, 0) << fromFile.err;
    EXPECT_EQ(manifestFaceRes(root_ / "a"), 8);
    // The flag wins over the file, before or after --config, and --config may come first.
    const ChildResult overridden = cook({"--config", level.string(), "bake", kRoom.string(),
                                         "--face-res", "4", "--out", (root_ / "b").string()});
    ASSERT_EQ(overridden.status, 0) << overridden.err;
    EXPECT_EQ(manifestFaceRes(root_ / "b"), 4);
    // Without the file the default (256) would apply: the file really set the option.
    EXPECT_NE(manifestFaceRes(root_ / "a"), 256);
}

TEST_F(CookConfig, BadConfigFileIsACommandLineError) {
    const std::string out = (root_ / "probe").string();
    expectUsageError(
        {"bake", kRoom.string(), "--out", out, "--config", (root_ / "none.toml").string()},
        {"--config", "none.toml"});
    const fs::path typo = writeConfig("typo.toml", "[bake]\nface-rez = 8\n");
    expectUsageError({"bake", kRoom.string(), "--out", out, "--config", typo.string()},
                     {"--config", "face-rez"});
    // A value from the file is validated like the flag's.
    const fs::path range = writeConfig("range.toml", "[bake]\nface-res = 5000\n");
    expectUsageError({"bake", kRoom.string(), "--out", out, "--config", range.string()},
                     {"--face-res"});
}

TEST_F(CookConfig, FlagsOfTheOtherFlavourAreRefusedNotIgnored) {
    const std::string scene = kRoom.string(), out = (root_ / "probe").string();
    expectUsageError({"bake", scene, "--out", out, "--flavour", "lightfield", "--face-res", "64"},
                     {"--face-res", "lightfield"});
    expectUsageError(
        {"bake", scene, "--out", out, "--flavour", "lightfield", "--layers", "objects"},
        {"--layers", "lightfield"});
    expectUsageError({"bake", scene, "--out", out, "--flavour", "distance", "--cameras", "8"},
                     {"--cameras", "distance"});
    // The default flavour is distance; every light-field flag is refused there.
    for (const char* flag : {"--cell-size", "--cameras", "--image-res"})
        expectUsageError({"bake", scene, "--out", out, flag, "8"}, {flag, "distance"});
    expectUsageError({"bake", scene, "--out", out, "--cell-center", "0,1,0"},
                     {"--cell-center", "distance"});
    expectUsageError({"bake", scene, "--out", out, "--compress", "bc1"},
                     {"--compress", "distance"});
    // --compress is both flavours' flag, each with its own codec.
    expectUsageError({"bake", scene, "--out", out, "--flavour", "lightfield", "--compress", "bc6h"},
                     {"--compress", "bc6h", "lightfield"});
    expectUsageError({"bake", scene, "--out", out, "--flavour", "pem", "--compress", "bc1"},
                     {"--compress", "bc1", "pem"});
    // From a config file too.
    const fs::path level = writeConfig("lf.toml", "[bake]\ncameras = 8\n");
    expectUsageError({"bake", scene, "--out", out, "--config", level.string()},
                     {"--cameras", "distance"});
}

TEST_F(CookConfig, HelpOfEverySubcommandNamesEveryFlag) {
    const std::vector<std::pair<std::string, std::vector<std::string>>> flags = {
        {"inspect", {"FILE"}},
        {"plan", {"SCENE", "--probe", "--max-error-deg", "--json"}},
        {"bake",
         {"SCENE", "--out", "--flavour", "--probe", "--sky", "--face-res", "--layers",
          "--cell-size", "--cell-center", "--cameras", "--image-res", "--compress", "--config",
          "130 cancelled"}},
    };
    for (const auto& [sub, names] : flags) {
        const ChildResult r = cook({sub, "--help"});
        EXPECT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("usage: specula-cook " + sub), std::string::npos) << r.out;
        for (const std::string& n : names)
            EXPECT_NE(r.out.find(n), std::string::npos) << sub << " --help must name " << n;
    }
    const ChildResult tool = cook({"--help"});
    for (const char* s : {"inspect", "bake", "plan", "--config"})
        EXPECT_NE(tool.out.find(s), std::string::npos) << "--help must name " << s;
}
