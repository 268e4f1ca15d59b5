// A PEM baked along a camera path that looks away (issue 34): the bake used to fail as a
// whole when one sample's view held no reflector pixel. Now that sample is left out with a
// warning, the asset keeps the samples that see the reflector (their parameters say where
// they lie on the path), and the runtime blends across the gap. A path that never sees a
// reflector is still an error naming the sample.
#include "support/csv_table.h"
#include "support/shell_tool.h"

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace specula::test;

namespace {

const fs::path kRoomCameraPath = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room_camera_path.gltf";
const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kSandbox = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";

// The room with its camera animation replaced: five keys (t = 0 .. 4) at the camera's still
// pose, which sees the mirror, except those in `away`, turned half a circle about the
// vertical so the camera faces the back wall. The keys' buffer is written as a file beside.
fs::path roomLookingAway(const fs::path& dir, const std::array<bool, 5>& away) {
    fs::copy(kRoomCameraPath.parent_path(), dir);
    const fs::path scene = dir / kRoomCameraPath.filename();
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(scene));
    nlohmann::json camera;
    for (const nlohmann::json& n : gltf["nodes"])
        if (n.contains("camera")) camera = n;
    const glm::quat still(camera["rotation"][3].get<float>(), camera["rotation"][0].get<float>(),
                          camera["rotation"][1].get<float>(), camera["rotation"][2].get<float>());
    const glm::quat turned = glm::angleAxis(glm::pi<float>(), glm::vec3(0, 1, 0)) * still;
    // The layout of the animation's buffer: 5 times, 5 translations, 5 rotations (x, y, z, w).
    std::array<float, 5 + 15 + 20> keys{};
    for (int k = 0; k < 5; ++k) {
        keys[std::size_t(k)] = float(k);
        for (int c = 0; c < 3; ++c)
            keys[std::size_t(5 + 3 * k + c)] = camera["translation"][std::size_t(c)].get<float>();
        const glm::quat q = away[std::size_t(k)] ? turned : still;
        const std::array<float, 4> xyzw{q.x, q.y, q.z, q.w};
        for (int c = 0; c < 4; ++c)
            keys[std::size_t(20 + 4 * k + c)] = xyzw[std::size_t(c)];
    }
    std::ofstream(dir / "keys.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(keys.data()), sizeof keys);
    const std::size_t animationBuffer = gltf["bufferViews"][gltf["accessors"][std::size_t(
        gltf["animations"][0]["samplers"][0]["input"].get<int>())]["bufferView"]
                                                                .get<int>()]["buffer"];
    gltf["buffers"][animationBuffer] = {{"uri", "keys.bin"}, {"byteLength", sizeof keys}};
    std::ofstream(scene) << gltf.dump();
    return scene;
}

ToolRun bakeAlongTheCameraPath(const fs::path& scene, const fs::path& out) {
    return runShellTool(kCook, "bake " + shellQuote(scene.string()) +
                                   " --flavour pem --path camera --samples 3 --face-res 16 "
                                   "--image-size 64x48 --local-layer off --out " +
                                   shellQuote(out.string()));
}

} // namespace

TEST(PemCameraPath, ASampleThatSeesNoReflectorIsLeftOutAndSaidSo) {
    TempDir dir("pem-look-away");
    // Samples at t = 0, 1/2, 1 are keys 0, 2 and 4: the middle one faces the wall.
    const fs::path scene = roomLookingAway(dir.path / "scene", {false, false, true, false, false});
    const fs::path probe = dir.path / "probe";
    const ToolRun r = bakeAlongTheCameraPath(scene, probe);
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string said = r.out + r.err;
    EXPECT_NE(said.find("parameter sample 1 (t = 0.500000): the camera sees no reflector pixel "
                        "there; the sample is left out"),
              std::string::npos)
        << said;
    EXPECT_NE(said.find("left out 1 of 3 samples (no reflector pixel in view) at t = 0.5"),
              std::string::npos)
        << said;
    EXPECT_EQ(said.find("nan"), std::string::npos) << said;
    const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(probe / "manifest.json"));
    ASSERT_EQ(manifest["samples"].size(), 2u);
    EXPECT_EQ(manifest["samples"][0]["parameter"].get<float>(), 0.f);
    EXPECT_EQ(manifest["samples"][1]["parameter"].get<float>(), 1.f);

    // The sandbox walks the asset along the same path: the two ends are samples' own views,
    // the middle frame sees no reflector and measures nothing.
    const fs::path walk = dir.path / "walk";
    const ToolRun w =
        runShellTool(kSandbox, "walk " + shellQuote((probe / "manifest.json").string()) +
                                   " --headless --frames 3 --size 64x48 --compare --out " +
                                   shellQuote(walk.string()));
    ASSERT_EQ(w.status, 0) << w.err;
    const CsvTable frames = readCsv(walk / "frames.csv");
    ASSERT_EQ(frames.size(), 3u);
    EXPECT_EQ(frames[1].at("psnr_full"), "none");
    for (const std::size_t end : {std::size_t(0), std::size_t(2)})
        EXPECT_GE(num(frames[end], "psnr_full"), 30.0) << "frame " << end << ": a sample's view";
}

// The same bake as shards (the farm's way): the trace shard of the blind sample stores an
// empty trace, its sample shard says "left out", and the merge writes the same folder.
TEST(PemCameraPath, ShardsLeaveTheSameSampleOutAsOneMachine) {
    TempDir dir("pem-look-away-shards");
    const fs::path scene = roomLookingAway(dir.path / "scene", {false, false, true, false, false});
    const fs::path plain = dir.path / "plain", store = dir.path / "store";
    ASSERT_EQ(bakeAlongTheCameraPath(scene, plain).status, 0);
    const std::string args = " --flavour pem --path camera --samples 3 --face-res 16 "
                             "--image-size 64x48 --local-layer off";
    const ToolRun list = runShellTool(kCook, "shards " + shellQuote(scene.string()) + args +
                                                 " --out " + shellQuote(store.string()));
    ASSERT_EQ(list.status, 0) << list.err;
    for (int trace = 0; trace < 3; ++trace) {
        const ToolRun shard = runShellTool(kCook, "bake-shard " + shellQuote(store.string()) +
                                                      " --shard " + std::to_string(trace));
        ASSERT_EQ(shard.status, 0) << shard.err;
    }
    const ToolRun merge = runShellTool(kCook, "merge " + shellQuote(store.string()));
    ASSERT_EQ(merge.status, 0) << merge.err;
    EXPECT_NE(merge.out.find("warning: parameter sample 1 (t = 0.500000): the camera sees no "
                             "reflector pixel"),
              std::string::npos)
        << merge.out;
    for (const fs::directory_entry& f : fs::directory_iterator(plain)) {
        if (f.path().filename() == "manifest.json") continue; // names its own folder
        const fs::path merged = store / "pem" / f.path().filename();
        ASSERT_TRUE(fs::exists(merged)) << merged;
        EXPECT_TRUE(fileLines(merged) == fileLines(f.path())) << merged << " differs";
    }
    const nlohmann::json manifest =
        nlohmann::json::parse(std::ifstream(store / "pem" / "manifest.json"));
    ASSERT_EQ(manifest["samples"].size(), 2u);
    EXPECT_EQ(manifest["samples"][1]["parameter"].get<float>(), 1.f);
}

TEST(PemCameraPath, APathThatNeverSeesAReflectorIsAnErrorNamingTheSample) {
    TempDir dir("pem-never");
    const fs::path scene = roomLookingAway(dir.path / "scene", {true, true, true, true, true});
    const fs::path probe = dir.path / "probe";
    const ToolRun r = bakeAlongTheCameraPath(scene, probe);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("parameter sample 0 (t = 0.000000): no reflector pixel"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(probe / "manifest.json"));
}
