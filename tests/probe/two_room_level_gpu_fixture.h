#pragma once
// The fixture of the level GPU tests: a headless GL context for the suite, and the bundled
// two-room scene baked as a level of distance probes at 64^2 faces, unplanned (one
// composite a probe), into the test's scratch folder.
#include "assetcooker/lib/level_bake.h"
#include "engine/gpu/context.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"

#include <string>

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

    // The level's index file.
    std::string bake(ProbeRoom& room) {
        LevelCookOptions o;
        o.cook.scene = kTwoRoomsScene;
        o.cook.out = (root_ / "level").string();
        DistanceCookSettings d;
        d.faceRes = 64;
        d.planned = false;
        o.cook.flavour = d;
        o.cook.progress = false;
        return cookLevel(room.probeScene(), o, nullptr).index;
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
