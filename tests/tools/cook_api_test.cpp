// The cooking API in-process: one call per flavour turns a scene into a cooked folder whose
// manifest a loader reads once (readCookedProbeFacts), and the markup becomes components
// without the sandbox (attachProbeComponents).
#include "assetcooker/lib/bake/cook.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "engine/core/error.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>

#include <fstream>

namespace specula {
namespace {

namespace fs = std::filesystem;

const std::string kRoom = std::string(SPECULA_SOURCE_DIR) + "/assets/room/room.gltf";

class CookApi : public test::ScratchDirTest {
protected:
    CookApi() : ScratchDirTest("specula-cook-api") {}

    CookResult cook(const CookFlavour& flavour, const std::string& dir) {
        CookOptions o;
        o.scene = kRoom;
        o.out = (root_ / dir).string();
        o.flavour = flavour;
        o.progress = false;
        return cookProbe(o, nullptr);
    }
};

TEST_F(CookApi, EachFlavourCooksAFolderWhoseManifestNamesItsFlavourAndScene) {
    DistanceCookSettings d;
    d.faceRes = 16;
    d.measuredPlan = false; // the analytic plan's layers (the measured plan: tests/plan)
    const CookResult rd = cook(d, "distance");
    ASSERT_TRUE(std::holds_alternative<DistanceProbeAsset>(rd.asset));
    EXPECT_GT(std::get<DistanceProbeAsset>(rd.asset).layers.size(), 1u);
    const CookedProbeFacts fd = readCookedProbeFacts(rd.manifest);
    EXPECT_EQ(fd.flavour, "distance");
    EXPECT_EQ(fd.source, kRoom);
    EXPECT_TRUE(fd.skyFile.empty()); // no sky given: black, no sky file
    EXPECT_EQ(readDistanceProbe(rd.manifest).faceRes, 16);

    LightFieldCookSettings l;
    l.cameras = 4;
    l.imageRes = 8;
    l.cellSize = 1.25f;
    const CookResult rl = cook(l, "lightfield");
    ASSERT_TRUE(std::holds_alternative<LightFieldAsset>(rl.asset));
    EXPECT_EQ(rl.cellSize, 1.25f);
    EXPECT_EQ(readCookedProbeFacts(rl.manifest).flavour, "lightfield");
    const LightFieldAsset a = readLightFieldProbe(rl.manifest);
    EXPECT_EQ(a.cameras, 4);
    EXPECT_EQ(a.cellSize, 1.25f);
}

TEST_F(CookApi, RefusesAFolderItMayNotReplaceBeforeOpeningTheScene) {
    fs::create_directories(root_ / "mine");
    std::ofstream(root_ / "mine" / "notes.txt") << "a user's file";
    CookOptions o;
    o.scene = (root_ / "missing.gltf").string(); // never opened: the folder is refused first
    o.out = (root_ / "mine").string();
    o.progress = false;
    try {
        cookProbe(o, nullptr);
        FAIL() << "expected the folder to be refused";
    } catch (const Error& e) {
        // The folder is named, not the scene: the scene was never opened.
        EXPECT_EQ(e.file(), o.out) << e.what();
        EXPECT_EQ(std::string(e.what()).find("missing.gltf"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::exists(root_ / "mine" / "notes.txt"));
}

TEST_F(CookApi, ManifestFactsRefuseAnotherFormatVersionNamingTheField) {
    const fs::path m = root_ / "manifest.json";
    std::ofstream(m) << R"({"format": "specula-probe", "version": 4, "flavour": "distance"})";
    try {
        readCookedProbeFacts(m.string());
        FAIL() << "expected version 4 (newer than the runtime's 3.x) to be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), m.string());
        EXPECT_EQ(e.field(), "version");
    }
}

TEST(ProbeSetup, AttachProbeComponentsGivesEveryReflectorMeshAReflectorOfTheNewProbe) {
    ProbeScene scene(kRoom, "");
    ASSERT_FALSE(scene.markup.reflectors.empty());
    ReflectionProbe p;
    p.asset = "probe/manifest.json";
    const ecs::Entity first = attachProbeComponents(scene.registry, scene.markup, p);
    const ecs::Entity second = attachProbeComponents(scene.registry, scene.markup, p, first);
    EXPECT_FALSE(scene.registry.valid(first)); // replaced, not left behind
    ASSERT_TRUE(scene.registry.valid(second));
    EXPECT_EQ(scene.registry.get<ReflectionProbe>(second).asset, "probe/manifest.json");
    std::size_t meshes = 0;
    for (const ReflectorMarkup& r : scene.markup.reflectors)
        for (ecs::Entity e : r.meshes) {
            ++meshes;
            const Reflector* refl = scene.registry.find<Reflector>(e);
            ASSERT_NE(refl, nullptr) << r.node;
            EXPECT_EQ(refl->probe, second) << r.node;
            EXPECT_EQ(refl->fresnelF0, r.f0) << r.node;
        }
    EXPECT_GT(meshes, 0u);
}

} // namespace
} // namespace specula
