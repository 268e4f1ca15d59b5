// Big scenes within memory (issue 34): a 2,000-node room used to make every candidate of the
// measured plan refuse "at most 63 object layers" and `bake` write a 2,002-layer asset that
// the walk refused; --face-res 4096 died on a bare std::bad_alloc after minutes. Now the
// plan packs near objects into at most 63 object layers (plan_layer_packing.h), a bake that
// would give each object its own layer past the cap is refused before any face is rendered,
// and the faces' memory is estimated before it is allocated (refused with the figures).
#include "support/shell_tool.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace fs = std::filesystem;
using namespace specula::test;

namespace {

const fs::path kCook = fs::path(SPECULA_BIN_DIR) / "specula-cook";
const fs::path kSandbox = fs::path(SPECULA_BIN_DIR) / "specula-sandbox";
const fs::path kRoom = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";

ToolRun cook(const std::string& args, const std::string& env = "") {
    return runShellTool(kCook, args, env + "timeout 120 ");
}

// The bundled room with `count` small boxes (the red column's mesh, scaled to 5-25 cm)
// scattered through it outside a 1.2 m sphere about the probe, each its own root node.
fs::path clutteredRoom(const fs::path& dir, int count) {
    fs::copy(kRoom.parent_path(), dir);
    const fs::path scene = dir / kRoom.filename();
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(scene));
    int box = -1;
    for (std::size_t m = 0; m < gltf["meshes"].size(); ++m)
        if (gltf["meshes"][m]["name"] == "column_red") box = int(m);
    EXPECT_GE(box, 0);
    std::mt19937 rng(34);
    std::uniform_real_distribution<float> xz(-3.8f, 3.8f), y(0.1f, 3.8f), size(0.05f, 0.25f);
    for (int i = 0; i < count; ++i) {
        float p[3];
        do
            p[0] = xz(rng), p[1] = y(rng), p[2] = xz(rng);
        while (p[0] * p[0] + (p[1] - 1.2f) * (p[1] - 1.2f) + p[2] * p[2] < 1.44f);
        const float s = size(rng);
        gltf["scenes"][0]["nodes"].push_back(gltf["nodes"].size());
        // The column's mesh is 1 x 1 x 1 under its node's 0.3 x 3 x 0.3 scale.
        gltf["nodes"].push_back({{"name", "box_" + std::to_string(i)},
                                 {"mesh", box},
                                 {"translation", {p[0], p[1], p[2]}},
                                 {"scale", {s, s, s}}});
    }
    std::ofstream(scene) << gltf.dump();
    return scene;
}

} // namespace

TEST(BigScene, TwoThousandNodesArePlannedBakedAndWalkedWithinTheLayerCap) {
    TempDir dir("big-scene");
    const fs::path scene = clutteredRoom(dir.path / "scene", 2000);
    // One layer per object: refused before any face is rendered, naming the count and the cap.
    const fs::path objects = dir.path / "objects";
    const ToolRun refused =
        cook("bake " + shellQuote(scene.string()) + " --layers objects --face-res 8 --out " +
             shellQuote(objects.string()));
    EXPECT_EQ(refused.status, 1) << refused.err;
    EXPECT_NE(refused.err.find("object layers (one per object): the runtime reads at most 63"),
              std::string::npos)
        << refused.err;
    EXPECT_FALSE(fs::exists(objects));

    // The plan packs them: a layered asset the runtime reads.
    const fs::path probe = dir.path / "probe";
    const ToolRun baked = cook("bake " + shellQuote(scene.string()) +
                               " --plan analytic --face-res 8 --out " + shellQuote(probe.string()));
    ASSERT_EQ(baked.status, 0) << baked.err;
    const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(probe / "manifest.json"));
    const std::size_t layers = manifest["layers"].size();
    std::printf("[big scene] 2000 boxes baked into %zu layers\n", layers);
    EXPECT_GT(layers, 2u);
    EXPECT_LE(layers, 64u);
    const ToolRun walk =
        runShellTool(kSandbox, "walk " + shellQuote((probe / "manifest.json").string()) +
                                   " --method layered --headless --frames 1 "
                                   "--size 48x36 --out " +
                                   shellQuote((dir.path / "walk").string()));
    EXPECT_EQ(walk.status, 0) << walk.err;
}

TEST(BigScene, FacesThatWouldNotFitInMemoryAreRefusedWithTheFigures) {
    TempDir dir("big-faces");
    const std::string limit = "SPECULA_MEMORY_LIMIT_MIB=256 ";
    // The measured plan holds two probes of the room's 14 layers, at 512^2 and 256^2:
    // 14 x 6 x (512^2 + 256^2) x 16 B = 0.41 GiB.
    for (const std::string& command : {std::string("bake"), std::string("plan")}) {
        const fs::path out = dir.path / command;
        const ToolRun r = cook(command + " " + shellQuote(kRoom.string()) + " --face-res 512" +
                                   (command == "bake" ? " --out " + shellQuote(out.string()) : ""),
                               limit);
        EXPECT_EQ(r.status, 1) << command << "\n" << r.err;
        EXPECT_NE(r.err.find("--face-res: the measured plan at face_res 512 and 256 with 14 "
                             "layers needs 0.4 GiB for its faces; 0.2 GiB of memory is available"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    // Without the plan the bake alone is weighed: the composite and the room's 13 objects,
    // 14 x 6 x 512^2 x 16 B = 0.33 GiB.
    const ToolRun objects =
        cook("bake " + shellQuote(kRoom.string()) + " --layers objects --face-res 512 --out " +
                 shellQuote((dir.path / "objects").string()),
             limit);
    EXPECT_EQ(objects.status, 1) << objects.err;
    EXPECT_NE(objects.err.find("a bake at face_res 512 with 14 layers needs 0.3 GiB"),
              std::string::npos)
        << objects.err;
    // Within the bound the same bake runs.
    const ToolRun small =
        cook("bake " + shellQuote(kRoom.string()) + " --layers objects --face-res 64 --out " +
                 shellQuote((dir.path / "small").string()),
             limit);
    EXPECT_EQ(small.status, 0) << small.err;
}
