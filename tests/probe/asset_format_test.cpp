// Versioned manifests (issue 36, item 5): "format": {"name", "major", "minor"}. A reader takes
// its own major with a newer minor, ignoring the members it does not know and naming each once
// in one warning (found through the embedded JSON Schemas, docs/formats/); it refuses a newer
// major naming both versions, and an older one naming the command that re-cooks it. Manifests
// written before the minor existed read as 2.0 (probes) and 1.0 (levels).
#include "components/reflection_probe/asset_format.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "components/reflection_probe/level_index.h"
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/manifest_schema.h"
#include "engine/core/error.h"
#include "engine/core/warning.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace specula {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Collects the runtime's warnings for the test's lifetime, then restores the tools' log.
struct CapturedWarnings {
    std::vector<std::string> lines;
    CapturedWarnings() {
        setWarningHandler([this](std::string_view m) { lines.emplace_back(m); });
    }
    ~CapturedWarnings() { setWarningHandler({}); }
};

std::size_t occurrences(const std::string& text, const std::string& word) {
    std::size_t n = 0;
    for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
        ++n;
    return n;
}

class AssetFormatTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("specula-asset-format-" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        original_ = readDistanceProbe(SPECULA_SOURCE_DIR "/tests/fuzz/data/probe/manifest.json");
        writeDistanceProbe(original_, dir_.string(), "scene.gltf");
        std::ifstream in(manifest());
        written_ = json::parse(in);
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string manifest() const { return (dir_ / "manifest.json").string(); }
    // Rewrites the manifest as a writer of that version would: sealed over its new fields.
    void rewrite(json m) const {
        m["seal"] = manifestSeal(m);
        std::ofstream(manifest()) << m.dump(1);
    }

    fs::path dir_;
    DistanceProbeAsset original_;
    json written_;
};

TEST_F(AssetFormatTest, AnUncompressedProbeStatesTheOlderMajorSoOlderRuntimesReadIt) {
    // Nothing of 3.x (compression) is used: 2.x, which a 2.x runtime reads as it always did.
    EXPECT_EQ(written_["format"], formatJson(kProbeFormat, false));
    EXPECT_EQ(written_["format"]["major"], 2);
    EXPECT_EQ(written_["format"]["minor"], kProbeFormat.plainVersion.minor);
    EXPECT_FALSE(written_.contains("version"));
    EXPECT_EQ(undeclaredMembers(written_, "probe-distance"), std::vector<std::string>{});
}

TEST_F(AssetFormatTest, ANewerMinorLoadsAndNamesWhatItIgnoresOnce) {
    json m = written_;
    m["format"]["major"] = kProbeFormat.major;
    m["format"]["minor"] = kProbeFormat.minor + 1;
    m["tint"] = {1, 0.5, 0.25};
    for (json& layer : m["layers"])
        layer["anisotropy"] = 0.3;
    rewrite(m);
    CapturedWarnings warnings;
    const DistanceProbeAsset read = readDistanceProbe(manifest());
    EXPECT_EQ(read.faceRes, original_.faceRes);
    EXPECT_EQ(read.layers.size(), original_.layers.size());
    ASSERT_EQ(warnings.lines.size(), 1u);
    const std::string& w = warnings.lines[0];
    const std::string major = std::to_string(kProbeFormat.major) + ".";
    const std::string newer = major + std::to_string(kProbeFormat.minor + 1);
    EXPECT_NE(w.find(manifest()), std::string::npos) << w;
    EXPECT_NE(w.find("asset format " + newer + " is newer than this runtime (" + major +
                     std::to_string(kProbeFormat.minor) + ")"),
              std::string::npos)
        << w;
    EXPECT_EQ(occurrences(w, "tint"), 1u) << w;
    EXPECT_EQ(occurrences(w, "layers[].anisotropy"), 1u) << w; // every layer has it: once
    EXPECT_EQ(occurrences(w, "range_D"), 0u) << w;             // a member it knows
}

TEST_F(AssetFormatTest, ANewerMinorWithNothingNewLoadsSilently) {
    json m = written_;
    m["format"]["major"] = kProbeFormat.major;
    m["format"]["minor"] = kProbeFormat.minor + 4;
    rewrite(m);
    CapturedWarnings warnings;
    EXPECT_EQ(readDistanceProbe(manifest()).faceRes, original_.faceRes);
    EXPECT_TRUE(warnings.lines.empty());
}

TEST_F(AssetFormatTest, ANewerMajorIsRefusedNamingBothVersions) {
    json m = written_;
    m["format"]["major"] = 4;
    m["format"]["minor"] = 1;
    rewrite(m);
    try {
        readDistanceProbe(manifest());
        FAIL() << "a newer major was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "format.major");
        EXPECT_NE(std::string(e.what()).find(
                      "asset format 4.1 is newer than this runtime (3.x): re-cook it"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(AssetFormatTest, AnOpenExrAssetNamesItsFormatAndTheCommandThatReCooksIt) {
    json m = written_;
    m["format"] = "specula-probe";
    m["version"] = 1;
    rewrite(m);
    try {
        readDistanceProbe(manifest());
        FAIL() << "format 1 was read";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "version");
        const std::string what = e.what();
        EXPECT_NE(what.find("asset format 1.0 (OpenEXR textures"), std::string::npos) << what;
        EXPECT_NE(what.find("specula-cook bake"), std::string::npos) << what;
    }
}

TEST_F(AssetFormatTest, AManifestWrittenBeforeTheMinorReadsAsTwoZero) {
    json m = written_;
    m["format"] = "specula-probe";
    m["version"] = 2;
    rewrite(m);
    CapturedWarnings warnings;
    EXPECT_EQ(readDistanceProbe(manifest()).layers.size(), original_.layers.size());
    EXPECT_TRUE(warnings.lines.empty());
}

TEST(AssetFormat, ALevelOfANewerMinorNamesItsNewMembers) {
    LevelIndex index;
    index.source = "scene.gltf";
    index.flavour = "distance";
    for (int i = 0; i < 2; ++i) {
        LevelProbeEntry e;
        e.volume.name = "p" + std::to_string(i);
        e.volume.position = glm::vec3(float(i) * 4.f, 1.f, 0.f);
        e.volume.proxy = {e.volume.position - glm::vec3(2.f), e.volume.position + glm::vec3(2.f)};
        e.volume.influence.box = e.volume.proxy;
        e.folder = e.volume.name;
        e.manifestChecksum = "fnv1a64:0000000000000000";
        e.inputs = {"fnv1a64:0000000000000001", "fnv1a64:0000000000000002", "none"};
        index.probes.push_back(e);
    }
    json j = toJson(index);
    EXPECT_EQ(j["format"], formatJson(kLevelFormat));
    EXPECT_EQ(undeclaredMembers(j, "level"), std::vector<std::string>{});
    j["format"]["minor"] = kLevelFormat.minor + 1;
    for (json& p : j["probes"])
        p["lod_bias"] = 1;
    j["streaming"] = {{"budget_mib", 64}};
    CapturedWarnings warnings;
    EXPECT_EQ(levelIndexFromJson(j, "level.json").probes.size(), 2u);
    ASSERT_EQ(warnings.lines.size(), 1u);
    EXPECT_EQ(occurrences(warnings.lines[0], "probes[].lod_bias"), 1u) << warnings.lines[0];
    EXPECT_EQ(occurrences(warnings.lines[0], "streaming"), 1u) << warnings.lines[0];

    j["format"]["major"] = kLevelFormat.major + 1;
    EXPECT_THROW(levelIndexFromJson(j, "level.json"), Error);
    // A level index written before 1.1: "format" a string, "version" the major.
    j["format"] = "specula-level";
    j["version"] = 1;
    EXPECT_EQ(levelIndexFromJson(j, "level.json").probes.size(), 2u);
}

TEST(AssetFormat, EveryManifestKindHasItsSchemaCompiledIn) {
    for (const char* name : {"probe-distance", "probe-lightfield", "probe-pem", "level"}) {
        const auto text = manifestSchemaText(name);
        ASSERT_TRUE(text.has_value()) << name;
        EXPECT_TRUE(json::accept(*text)) << name;
    }
    EXPECT_THROW(undeclaredMembers(json::object(), "probe-teapot"), Error);
}

} // namespace
} // namespace specula
