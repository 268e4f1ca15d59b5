// Glossy reflectors (issue 14): the distance bake writes the composite's GGX prefiltered chain
// beside the layers when the scene needs it, and the reader gives it back exactly as
// prefilterGgx made it, refusing a level file that is corrupt, of the wrong size or another
// probe's, naming the manifest's glossy.levels[k]. A manifest without "glossy" reads as before.
#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/image/ggx_prefilter.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"
#include "support/scratch_dir_test.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>

namespace specula {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kRoomDir = fs::path(SPECULA_SOURCE_DIR) / "assets/room";
const std::string kRoom = (kRoomDir / "room.gltf").string();
const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
constexpr int kFaceRes = 32;

json readJson(const fs::path& p) {
    std::ifstream in(p);
    return json::parse(in);
}

void writeJson(const fs::path& p, const json& j) {
    std::ofstream(p) << j.dump(2);
}

// Every float of two images, bit for bit (NaN-safe: compares the bits).
bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.channels == b.channels &&
           a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// The error a read throws (and fails the test when it reads).
Error readError(const fs::path& manifest) {
    try {
        readDistanceProbe(manifest.string());
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "expected " << manifest << " to be refused";
    return Error("read");
}

class GlossyBakeTest : public test::ScratchDirTest {
protected:
    GlossyBakeTest() : ScratchDirTest("specula-glossy-bake") {}

    CookResult cook(const std::string& scene, const std::string& dir, GlossyBake glossy,
                    int faceRes = kFaceRes) {
        DistanceCookSettings s;
        s.faceRes = faceRes;
        s.glossy = glossy;
        CookOptions o;
        o.scene = scene;
        o.out = (root_ / dir).string();
        o.flavour = s;
        o.progress = false;
        return cookProbe(o, nullptr);
    }

    // A copy of the room whose torus is a glossy reflector ("specula_reflector":
    // {"roughness": 0.3}); its mirrors and geometry are the room's.
    std::string roughRoom() {
        const fs::path dir = root_ / "rough_room";
        fs::create_directories(dir);
        for (const fs::directory_entry& e : fs::directory_iterator(kRoomDir))
            fs::copy_file(e.path(), dir / e.path().filename());
        json gltf = readJson(dir / "room.gltf");
        bool found = false;
        for (json& node : gltf["nodes"])
            if (node.value("name", "") == "torus") {
                node["extras"]["specula_reflector"] = {{"roughness", 0.3}};
                found = true;
            }
        EXPECT_TRUE(found) << "the room has no torus node";
        writeJson(dir / "room.gltf", gltf);
        return (dir / "room.gltf").string();
    }

    // A probe of the room baked with its glossy levels, into root_/dir.
    fs::path glossyProbe(const std::string& dir = "probe") {
        cook(kRoom, dir, GlossyBake::On);
        return root_ / dir / "manifest.json";
    }
};

// Rewrites a level's image through `edit` and stores its new checksum in the manifest, so
// only the content checks can refuse it.
void editLevel(const fs::path& manifest, std::size_t k, const std::function<void(Image&)>& edit) {
    json m = readJson(manifest);
    json& entry = m["glossy"]["levels"][k];
    const fs::path file = manifest.parent_path() / entry["file"].get<std::string>();
    Image img = readKtx2(file.string()).levels[0];
    edit(img);
    writeKtx2Cube(file.string(), img);
    entry["checksum"] = fileChecksum(file.string());
    writeJson(manifest, m);
}

TEST_F(GlossyBakeTest, OnWritesTheCompositesChainAndTheReaderGivesItBackBitForBit) {
    const CookResult r = cook(kRoom, "probe", GlossyBake::On);
    const int levels = GgxPrefilterOptions{}.levels;
    const std::size_t glossy = std::size_t(levels - 1);
    EXPECT_GT(r.prefilterSeconds, 0.0); // it ran, and is reported apart from the bake

    // The manifest lists one file per level above the composite, with its roughness.
    const json m = readJson(r.manifest);
    ASSERT_TRUE(m.contains("glossy")) << m.dump(1);
    const json& entries = m["glossy"]["levels"];
    ASSERT_EQ(entries.size(), glossy);
    for (std::size_t k = 0; k < glossy; ++k) {
        const int level = int(k) + 1;
        EXPECT_EQ(entries[k]["file"], "layer_00_ggx_" + std::to_string(level) + ".ktx2");
        // The roughness the asset's comment states (i / L) is the chain's own.
        EXPECT_NEAR(entries[k]["roughness"].get<double>(), double(level) / double(glossy), 1e-12);
        EXPECT_FLOAT_EQ(float(entries[k]["roughness"].get<double>()),
                        ggxChainRoughness(level, levels));
        const fs::path file =
            fs::path(r.manifest).parent_path() / entries[k]["file"].get<std::string>();
        ASSERT_TRUE(fs::is_regular_file(file)) << file;
        EXPECT_EQ(entries[k]["checksum"], fileChecksum(file.string()));
    }

    // What the reader returns is prefilterGgx of the composite it returns, bit for bit (float
    // EXR stores float32 exactly), and what the cooker held.
    const DistanceProbeAsset a = readDistanceProbe(r.manifest);
    ASSERT_EQ(a.glossyLevels.size(), glossy);
    GgxPrefilterOptions o;
    o.levels = levels;
    o.dInf = a.dInf;
    const CubeChain chain = prefilterGgx(a.layers[0].faces, o);
    ASSERT_EQ(chain.levels.size(), std::size_t(levels));
    const auto& cooked = std::get<DistanceProbeAsset>(r.asset);
    ASSERT_EQ(cooked.glossyLevels.size(), glossy);
    for (std::size_t k = 0; k < glossy; ++k)
        for (int f = 0; f < 6; ++f) {
            const Image& read = a.glossyLevels[k][std::size_t(f)];
            EXPECT_EQ(read.width, std::max(1, kFaceRes >> (k + 1))) << "level " << k + 1;
            EXPECT_EQ(read.height, read.width);
            EXPECT_TRUE(sameBits(read, chain.levels[k + 1][std::size_t(f)]))
                << "level " << k + 1 << " face " << f;
            EXPECT_TRUE(sameBits(read, cooked.glossyLevels[k][std::size_t(f)]))
                << "level " << k + 1 << " face " << f;
        }
}

TEST_F(GlossyBakeTest, AutoWritesNoLevelsForARoomOfMirrors) {
    ProbeScene room(kRoom, "");
    ASSERT_FALSE(room.markup.reflectors.empty());
    ASSERT_FALSE(hasGlossyReflector(room.markup)); // the room's reflectors are mirrors
    const CookResult r = cook(kRoom, "probe", GlossyBake::Auto);
    EXPECT_EQ(r.prefilterSeconds, 0.0);
    EXPECT_FALSE(readJson(r.manifest).contains("glossy"));
    for (const fs::directory_entry& e : fs::directory_iterator(root_ / "probe"))
        EXPECT_EQ(e.path().filename().string().find("ggx"), std::string::npos) << e.path();
    EXPECT_TRUE(readDistanceProbe(r.manifest).glossyLevels.empty());
}

TEST_F(GlossyBakeTest, AutoWritesTheLevelsWhenAReflectorIsRoughAndOffDoesNot) {
    const std::string scene = roughRoom();
    ProbeScene rough(scene, "");
    ASSERT_TRUE(hasGlossyReflector(rough.markup));

    // 24: not a power of two, so footprints overlap (levels 12, 6, 3, 1, 1).
    const CookResult r = cook(scene, "auto", GlossyBake::Auto, 24);
    EXPECT_GT(r.prefilterSeconds, 0.0);
    const DistanceProbeAsset a = readDistanceProbe(r.manifest);
    ASSERT_EQ(a.glossyLevels.size(), 5u);
    const int expected[] = {12, 6, 3, 1, 1};
    for (std::size_t k = 0; k < 5; ++k)
        EXPECT_EQ(a.glossyLevels[k][0].width, expected[k]);
    EXPECT_EQ(readJson(r.manifest)["glossy"]["levels"].size(), 5u);

    const CookResult off = cook(scene, "off", GlossyBake::Off, 24);
    EXPECT_EQ(off.prefilterSeconds, 0.0);
    EXPECT_FALSE(readJson(off.manifest).contains("glossy"));
    EXPECT_TRUE(readDistanceProbe(off.manifest).glossyLevels.empty());
}

TEST_F(GlossyBakeTest, AFlippedByteInALevelIsAChecksumErrorNamingTheLevel) {
    const fs::path manifest = glossyProbe();
    const fs::path file = manifest.parent_path() / "layer_00_ggx_3.ktx2";
    {
        std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
        f.seekg(-16, std::ios::end);
        char c = 0;
        f.get(c);
        f.seekp(-16, std::ios::end);
        f.put(char(c ^ 0x5a));
    }
    const Error e = readError(manifest);
    EXPECT_EQ(e.file(), manifest.string()) << e.what();
    EXPECT_EQ(e.field(), "glossy.levels[2].checksum") << e.what();
    EXPECT_NE(std::string(e.what()).find("layer_00_ggx_3.ktx2"), std::string::npos) << e.what();
}

TEST_F(GlossyBakeTest, ALevelOfTheWrongSizeIsRefusedNamingTheLevel) {
    const fs::path manifest = glossyProbe();
    // Level 3's file as level 2's, checksum and all: the header's size is refused.
    json m = readJson(manifest);
    m["glossy"]["levels"][1]["file"] = m["glossy"]["levels"][2]["file"];
    m["glossy"]["levels"][1]["checksum"] = m["glossy"]["levels"][2]["checksum"];
    writeJson(manifest, m);
    const Error e = readError(manifest);
    EXPECT_EQ(e.field(), "glossy.levels[1].pixelWidth") << e.what();
    EXPECT_NE(std::string(e.what()).find("layer_00_ggx_3.ktx2"), std::string::npos) << e.what();
}

TEST_F(GlossyBakeTest, ContentAndFieldsALevelCannotHoldAreRefusedNamingTheLevel) {
    struct Case {
        const char* name;
        std::function<void(const fs::path&)> damage;
        std::string field;
        std::string says = ""; // in the message, when given
    };
    const std::vector<Case> cases = {
        {"radiance NaN",
         [](const fs::path& m) { editLevel(m, 0, [](Image& i) { i.at(3, 5)[1] = NAN; }); },
         "glossy.levels[0].radiance"},
        {"radiance past kMaxRadiance",
         [](const fs::path& m) { editLevel(m, 1, [](Image& i) { i.at(0, 0)[0] = 1e30f; }); },
         "glossy.levels[1].radiance"},
        {"distance zero",
         [](const fs::path& m) { editLevel(m, 0, [](Image& i) { i.at(1, 1)[3] = 0.f; }); },
         "glossy.levels[0].distance"},
        // A valid distance that is not the composite's nearest under the texel: another
        // probe's level, or an edited one.
        {"distance not the footprint's min",
         [](const fs::path& m) {
             editLevel(m, 0, [](Image& i) { i.at(2, 20)[3] = i.at(2, 20)[3] * 1.5f; });
         },
         "glossy.levels[0].distance", "min distance over its footprint"},
        {"roughness not i / L",
         [](const fs::path& m) {
             json j = readJson(m);
             j["glossy"]["levels"][1]["roughness"] = 0.5;
             writeJson(m, j);
         },
         "glossy.levels[1].roughness"},
        {"missing file",
         [](const fs::path& m) { fs::remove(m.parent_path() / "layer_00_ggx_4.ktx2"); },
         "glossy.levels[3].file"},
        {"file outside the folder",
         [](const fs::path& m) {
             json j = readJson(m);
             j["glossy"]["levels"][0]["file"] = "../layer_00_ggx_1.ktx2";
             writeJson(m, j);
         },
         "glossy.levels[0].file"},
        {"no levels",
         [](const fs::path& m) {
             json j = readJson(m);
             j["glossy"]["levels"] = json::array();
             writeJson(m, j);
         },
         "glossy.levels"},
        {"not an object",
         [](const fs::path& m) {
             json j = readJson(m);
             j["glossy"] = 5;
             writeJson(m, j);
         },
         "glossy"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const fs::path manifest = glossyProbe("probe_" + std::to_string(i));
        cases[i].damage(manifest);
        const Error e = readError(manifest);
        EXPECT_EQ(e.field(), cases[i].field) << cases[i].name << ": " << e.what();
        EXPECT_NE(std::string(e.what()).find(cases[i].says), std::string::npos)
            << cases[i].name << ": " << e.what();
    }
}

TEST_F(GlossyBakeTest, TheWriterRefusesLevelsItsReaderWouldRefuseAndWritesNothing) {
    const CookResult r = cook(kRoom, "probe", GlossyBake::On);
    DistanceProbeAsset a = std::get<DistanceProbeAsset>(r.asset);
    std::swap(a.glossyLevels[1], a.glossyLevels[2]); // sizes 8 and 4 at each other's place
    const fs::path out = root_ / "swapped";
    try {
        writeDistanceProbe(a, out.string(), kRoom);
        FAIL() << "expected the swapped levels to be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "glossy.levels[1].size") << e.what();
        EXPECT_NE(std::string(e.what()).find("layer_00_ggx_2.ktx2"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(GlossyBakeTest, AManifestWithoutGlossyReadsAsBefore) {
    const fs::path manifest = glossyProbe();
    const DistanceProbeAsset with = readDistanceProbe(manifest.string());
    // What a cooker before glossy levels wrote: no "glossy", no level files.
    json m = readJson(manifest);
    m.erase("glossy");
    m.erase("seal"); // nor a seal
    writeJson(manifest, m);
    for (int i = 1; i <= 5; ++i)
        fs::remove(manifest.parent_path() / ("layer_00_ggx_" + std::to_string(i) + ".ktx2"));
    const DistanceProbeAsset without = readDistanceProbe(manifest.string());
    EXPECT_TRUE(without.glossyLevels.empty());
    ASSERT_EQ(without.layers.size(), with.layers.size());
    for (std::size_t i = 0; i < with.layers.size(); ++i)
        for (int f = 0; f < 6; ++f)
            EXPECT_TRUE(sameBits(without.layers[i].faces[std::size_t(f)],
                                 with.layers[i].faces[std::size_t(f)]));

    // The committed probe the fuzzers seed from, cooked before glossy levels existed.
    const DistanceProbeAsset old =
        readDistanceProbe(std::string(SPECULA_SOURCE_DIR) + "/tests/fuzz/data/probe/manifest.json");
    EXPECT_TRUE(old.glossyLevels.empty());
    EXPECT_FALSE(old.layers.empty());
}

TEST_F(GlossyBakeTest, TheCommandLineTakesGlossyAutoOnOff) {
    const std::string out = (root_ / "cli").string();
    const test::ToolRun on =
        test::runShellTool(kCook, "bake " + test::shellQuote(kRoom) + " --out " +
                                      test::shellQuote(out) + " --face-res 16 --glossy on");
    ASSERT_EQ(on.status, 0) << on.err;
    EXPECT_NE(on.out.find("prefiltering the composite"), std::string::npos) << on.out;
    EXPECT_NE(on.out.find("glossy: 5 GGX levels"), std::string::npos) << on.out;
    EXPECT_EQ(readDistanceProbe(out + "/manifest.json").glossyLevels.size(), 5u);

    // Off replaces the folder with one holding no level files.
    const test::ToolRun off =
        test::runShellTool(kCook, "bake " + test::shellQuote(kRoom) + " --out " +
                                      test::shellQuote(out) + " --face-res 16 --glossy off");
    ASSERT_EQ(off.status, 0) << off.err;
    EXPECT_FALSE(fs::exists(fs::path(out) / "layer_00_ggx_1.ktx2"));
    EXPECT_FALSE(readJson(fs::path(out) / "manifest.json").contains("glossy"));

    const test::ToolRun bad =
        test::runShellTool(kCook, "bake " + test::shellQuote(kRoom) + " --out " +
                                      test::shellQuote(out) + " --glossy sometimes");
    EXPECT_EQ(bad.status, 2) << bad.err;
    EXPECT_NE(bad.err.find("--glossy"), std::string::npos) << bad.err;

    const test::ToolRun lightField =
        test::runShellTool(kCook, "bake " + test::shellQuote(kRoom) + " --out " +
                                      test::shellQuote(out) + " --flavour lightfield --glossy on");
    EXPECT_EQ(lightField.status, 2) << lightField.err;
    EXPECT_NE(lightField.err.find("--glossy"), std::string::npos) << lightField.err;

    const test::ToolRun help = test::runShellTool(kCook, "bake --help");
    EXPECT_EQ(help.status, 0);
    EXPECT_NE(help.out.find("--glossy"), std::string::npos);
}

} // namespace
} // namespace specula
