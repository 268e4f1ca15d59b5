// The PEM's "camera" path (cameraPathView): the scene camera's glTF animation, first key at
// t = 0 and last at t = 1, against the keys scripts/make_room_camera_path.py wrote.
#include "assetcooker/lib/scene/probe_setup.h"
#include "engine/core/error.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <string>

namespace specula {
namespace {

const std::string kRoomDir = std::string(SPECULA_SOURCE_DIR) + "/assets/room/";

TEST(CameraPathView, RunsFromTheFirstKeyToTheLastLookingAtTheReflectors) {
    const ProbeScene scene(kRoomDir + "room_camera_path.gltf", "");
    EXPECT_TRUE(sceneCameraMoves(scene));
    // The script's dolly: x from -1.2 to 1.2 m over 4 s, linear, the eye aimed at (0, 1.2, 0).
    for (const float t : {0.f, 0.125f, 0.5f, 1.f}) {
        const CameraView v = cameraPathView(scene, 160, 120, t);
        const glm::vec3 eye = v.eye();
        EXPECT_LT(glm::length(eye - glm::vec3(-1.2f + 2.4f * t, 1.6f, 3.48f)), 1e-5f) << t;
        EXPECT_EQ(v.width, 160);
        EXPECT_EQ(v.height, 120);
        // The reflectors' centre projects near the image centre (exactly at the keys).
        const glm::vec4 clip = v.viewProj() * glm::vec4(0.f, 1.2f, 0.f, 1.f);
        EXPECT_LT(glm::length(glm::vec2(clip) / clip.w), t == 0.125f ? 0.05f : 1e-5f) << t;
    }
    // Outside [0, 1]: held at the ends.
    EXPECT_EQ(cameraPathView(scene, 64, 48, 2.f).view, cameraPathView(scene, 64, 48, 1.f).view);
}

TEST(CameraPathView, AStillCameraHasNoPathNamingTheScene) {
    const ProbeScene scene(kRoomDir + "room.gltf", "");
    EXPECT_FALSE(sceneCameraMoves(scene));
    try {
        cameraPathView(scene, 64, 48, 0.5f);
        ADD_FAILURE() << "a still camera gave a path";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "path");
        EXPECT_EQ(e.file(), kRoomDir + "room.gltf");
    }
}

} // namespace
} // namespace specula
