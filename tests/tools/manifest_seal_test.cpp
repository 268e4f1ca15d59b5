// A manifest edited by hand loads as what it now says, silently (issue 34: a PEM manifest's
// geometry or local layer edited, a distance probe's range). Every manifest Specula writes is
// now sealed with the checksum of its fields; a reader that finds them changed refuses,
// naming "seal" and how to load the edit on purpose (delete the seal).
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/pem/pem_asset.h"
#include "engine/core/error.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace fs = std::filesystem;
using namespace specula;
using namespace specula::test;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const std::string kRoom = SPECULA_SOURCE_DIR "/assets/room/room.gltf";

// Edits `manifest` with `edit`, then `read` must refuse it naming the seal; without the seal
// the edited manifest reads.
void expectSealHolds(const fs::path& manifest, const std::function<void(nlohmann::json&)>& edit,
                     const std::function<void()>& read) {
    ASSERT_NO_THROW(read()) << "the manifest as written must read";
    nlohmann::json j = nlohmann::json::parse(std::ifstream(manifest));
    ASSERT_TRUE(j.contains("seal"));
    edit(j);
    std::ofstream(manifest) << j.dump(2);
    try {
        read();
        ADD_FAILURE() << "an edited manifest read";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), manifest.string());
        EXPECT_EQ(e.field(), "seal");
        EXPECT_NE(std::string(e.what()).find("delete \"seal\""), std::string::npos) << e.what();
    }
    j.erase("seal");
    std::ofstream(manifest) << j.dump(2);
    EXPECT_NO_THROW(read()) << "unsealed on purpose, the edit reads";
}

} // namespace

TEST(ManifestSeal, AnEditedDistanceManifestIsRefusedNamingTheSeal) {
    TempDir dir("seal-distance");
    const fs::path probe = dir.path / "probe";
    ASSERT_EQ(runShellTool(kCook, "bake " + shellQuote(kRoom) + " --face-res 8 --out " +
                                      shellQuote(probe.string()))
                  .status,
              0);
    const fs::path manifest = probe / "manifest.json";
    expectSealHolds(
        manifest, [](nlohmann::json& j) { j["range_D"] = j["range_D"].get<double>() * 2.0; },
        [&] { readDistanceProbe(manifest.string()); });
}

TEST(ManifestSeal, AnEditedPemGeometryIsRefusedNamingTheSeal) {
    TempDir dir("seal-pem");
    const fs::path probe = dir.path / "probe";
    const ToolRun r = runShellTool(kCook, "bake " + shellQuote(kRoom) +
                                              " --flavour pem --samples 2 --face-res 8 "
                                              "--image-size 32x24 --out " +
                                              shellQuote(probe.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    const fs::path manifest = probe / "manifest.json";
    expectSealHolds(
        manifest, [](nlohmann::json& j) { j["geometry"] = "box"; },
        [&] { readPemProbe(manifest.string()); });
}
