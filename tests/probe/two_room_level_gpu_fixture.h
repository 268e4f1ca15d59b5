#pragma once
// The fixture of the level GPU tests: a headless GL context for the suite, and the bundled
// two-room scene baked as a level of distance probes at 64^2 faces, unplanned (one
// composite a probe), into the test's scratch folder.
#include "assetcooker/lib/level/level_bake.h"
#include "engine/context/context.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"

#include <string>
#include <utility>

namespace specula::test {

inline const std::string kTwoRoomsScene =
    std::string(SPECULA_SOURCE_DIR) + "/assets/two_rooms/two_rooms.gltf";

class TwoRoomLevelGpuTest : public ScratchDirTest {
protected:
    explicit TwoRoomLevelGpuTest(std::string prefix) : ScratchDirTest(std::move(prefix)) {}

    static void SetUpTestSuite() { context_ = gpu::GlContext::createHeadless().release(); }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }

    // The level's index file; `compression` and `glossy` for every probe.
    std::string bake(ProbeRoom& room, DistanceCompression compression = DistanceCompression::None,
                     GlossyBake glossy = GlossyBake::Auto) {
        LevelCookOptions o;
        o.cook.scene = kTwoRoomsScene;
        o.cook.out = (root_ / "level").string();
        DistanceCookSettings d;
        d.faceRes = 64;
        d.planned = false;
        d.compression = compression;
        d.glossy = glossy;
        o.cook.flavour = d;
        o.cook.progress = false;
        return cookLevel(room.probeScene(), o, nullptr).index;
    }

    // The level baked and drawn with the secant search (default blend and K), the mirror
    // sphere moved 1.2 m along x into the doorway: the setup of the doorway tests.
    // Returns the level's index file and the settings drawn.
    std::pair<std::string, DistanceLevel> setUpSecantDoorway(ProbeRoom& room) {
        const std::string index = bake(room);
        room.setReflectorOffset(glm::vec3(1.2f, 0.f, 0.f));
        DistanceLevel settings;
        settings.lookup.method = DistanceMethod::Secant;
        room.setProbe(index, settings);
        return {index, settings};
    }

    // Looking from room A at the doorway (the wall at x = 0), where the mirror moved 1.2 m
    // along x sits in both probes' influence.
    static CameraView doorwayCamera(int width, int height) {
        return CameraView::lookAt(glm::vec3(-1.4f, 1.5f, 1.0f), glm::vec3(0.2f, 1.2f, 0.f),
                                  glm::vec3(0, 1, 0), glm::radians(40.f), width, height);
    }

    static inline gpu::GlContext* context_ = nullptr;
};

} // namespace specula::test
