// Keyframed node transforms (engine/scene/animation.h) against closed forms, and the glTF
// loader's animation channels (gltf_animation.h) on the room whose camera dollies
// (scripts/make_room_camera_path.py), with bad input named by field.
#include "engine/core/error.h"
#include "engine/ecs/registry.h"
#include "engine/scene/animation.h"
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "support/gltf_load_error.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace specula;

namespace {

const fs::path kRoomDir = fs::path(SPECULA_SOURCE_DIR) / "assets" / "room";
const fs::path kCameraPath = kRoomDir / "room_camera_path.gltf";

// The script's keys: the eye at 0, 1, 2, 3, 4 s, always looking at the reflectors.
glm::vec3 scriptEye(float seconds) {
    return {-1.2f + 0.6f * seconds, 1.6f, 3.48f};
}
const glm::vec3 kTarget(0.f, 1.2f, 0.f);

// A cubic and its derivative, per component.
glm::vec3 cubic(float t) {
    return {t * t * t - 2.f * t * t + 0.5f * t + 1.f, -0.3f * t * t * t + t, 2.f * t * t - 1.f};
}
glm::vec3 cubicSlope(float t) {
    return {3.f * t * t - 4.f * t + 0.5f, -0.9f * t * t + 1.f, 4.f * t};
}

TEST(KeyframeTrack, CubicSplineReproducesACubicThroughItsKeysAndTangents) {
    // Hermite interpolation is exact for a cubic given its values and slopes at the keys,
    // whatever the key spacing.
    KeyframeTrack<glm::vec3> track;
    track.interpolation = Interpolation::CubicSpline;
    track.times = {0.f, 0.5f, 2.f};
    for (float t : track.times)
        track.values.insert(track.values.end(), {cubicSlope(t), cubic(t), cubicSlope(t)});
    for (float t = 0.f; t <= 2.f; t += 0.05f)
        EXPECT_LT(glm::length(track.sample(t) - cubic(t)), 1e-5f) << "t = " << t;
    EXPECT_EQ(track.sample(-1.f), cubic(0.f)); // held outside the keys
    EXPECT_EQ(track.sample(3.f), cubic(2.f));
}

TEST(KeyframeTrack, LinearAndStepBetweenKeys) {
    KeyframeTrack<glm::vec3> track;
    track.times = {1.f, 3.f};
    track.values = {glm::vec3(0.f, 2.f, 4.f), glm::vec3(2.f, 2.f, 0.f)};
    EXPECT_LT(glm::length(track.sample(1.5f) - glm::vec3(0.5f, 2.f, 3.f)), 1e-6f);
    EXPECT_EQ(track.sample(0.f), track.values[0]);
    track.interpolation = Interpolation::Step;
    EXPECT_EQ(track.sample(2.99f), track.values[0]);
    EXPECT_EQ(track.sample(3.f), track.values[1]);
}

TEST(KeyframeTrack, RotationsSlerpAlongTheShorterArc) {
    KeyframeTrack<glm::quat> track;
    track.times = {0.f, 1.f};
    const glm::vec3 y(0.f, 1.f, 0.f);
    // 90 degrees about +Y, given with a negative w: the same rotation as its negation.
    track.values = {glm::quat(1.f, 0.f, 0.f, 0.f), -glm::angleAxis(glm::half_pi<float>(), y)};
    const glm::vec3 x = track.sample(0.5f) * glm::vec3(1.f, 0.f, 0.f);
    const float c = std::cos(glm::quarter_pi<float>());
    EXPECT_LT(glm::length(x - glm::vec3(c, 0.f, -c)), 1e-6f); // 45 degrees, not 135 the other way
}

struct LoadedRoom {
    ecs::Registry registry;
    LoadedScene scene;
    ecs::Entity camera = ecs::kNullEntity;
    explicit LoadedRoom(const fs::path& p) : scene(loadGltf(p.string(), registry)) {
        for (ecs::Entity e : scene.entities)
            if (registry.find<Camera>(e)) camera = e;
    }
};

TEST(GltfAnimation, TheCameraFollowsItsKeysAndLooksWhereTheScriptAimedIt) {
    LoadedRoom room(kCameraPath);
    ASSERT_FALSE(room.camera.isNull());
    const NodeAnimation* a = room.registry.find<NodeAnimation>(room.camera);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->translation.times.size(), 5u);
    EXPECT_EQ(a->rotation.times.size(), 5u);
    EXPECT_TRUE(a->scale.empty());
    const auto span = animatedRange(room.registry, room.camera);
    ASSERT_TRUE(span.has_value());
    EXPECT_EQ(span->first, 0.f);
    EXPECT_EQ(span->second, 4.f);
    for (float seconds : {0.f, 1.f, 2.f, 3.f, 4.f}) {
        const glm::mat4 world = animatedWorld(room.registry, room.camera, seconds);
        const glm::vec3 eye(world[3]);
        EXPECT_LT(glm::length(eye - scriptEye(seconds)), 1e-5f) << seconds << " s";
        const glm::vec3 forward = -glm::normalize(glm::vec3(world[2]));
        EXPECT_GT(glm::dot(forward, glm::normalize(kTarget - eye)), 1.f - 1e-6f) << seconds;
    }
    // Linear between keys: half-way from 0 to 1 s.
    EXPECT_LT(glm::length(glm::vec3(animatedWorld(room.registry, room.camera, 0.5f)[3]) -
                          scriptEye(0.5f)),
              1e-5f);
    // Nothing else moves; the still room has no animation at all.
    for (ecs::Entity e : room.scene.entities)
        if (e != room.camera) {
            EXPECT_FALSE(animatedRange(room.registry, e).has_value());
        }
    LoadedRoom still(kRoomDir / "room.gltf");
    EXPECT_FALSE(animatedRange(still.registry, still.camera).has_value());
}

using test::expectLoadError;

// The glTF fuzz seed with one channel of each interpolation on node 0 (embedded keys 0, 0.5,
// 2 s): LINEAR translation, STEP rotation, CUBICSPLINE scale.
TEST(GltfAnimation, EachInterpolationLoadsFromAFile) {
    const fs::path seed =
        fs::path(SPECULA_SOURCE_DIR) / "tests/fuzz/corpus/gltf/Box_animated_embedded.gltf";
    ecs::Registry registry;
    const LoadedScene scene = loadGltf(seed.string(), registry);
    const NodeAnimation* a = nullptr;
    for (ecs::Entity e : scene.entities)
        if (registry.find<SceneNode>(e)->nodeIndex == 0) a = registry.find<NodeAnimation>(e);
    ASSERT_NE(a, nullptr);
    EXPECT_EQ(a->translation.interpolation, Interpolation::Linear);
    EXPECT_EQ(a->rotation.interpolation, Interpolation::Step);
    EXPECT_EQ(a->scale.interpolation, Interpolation::CubicSpline);
    EXPECT_EQ(a->scale.values.size(), 9u); // in-tangent, value, out-tangent a key
    EXPECT_LT(glm::length(a->translation.sample(0.25f) - glm::vec3(0.5f, 0.f, 0.f)), 1e-6f);
    // STEP holds key 1 (90 degrees about +Y) until key 2: +X turns to -Z.
    EXPECT_LT(glm::length(a->rotation.sample(1.9f) * glm::vec3(1.f, 0.f, 0.f) -
                          glm::vec3(0.f, 0.f, -1.f)),
              1e-5f);
    EXPECT_LT(glm::length(a->scale.sample(0.5f) - glm::vec3(2.f)), 1e-6f); // a key's value
}

// The camera-path room in `dir` (its room.bin beside it) with `edit` applied to its JSON.
template <typename Edit>
fs::path editedRoom(const test::TempDir& dir, const char* name, Edit edit) {
    nlohmann::json j = nlohmann::json::parse(std::ifstream(kCameraPath));
    fs::copy_file(kRoomDir / "room.bin", dir.path / "room.bin", fs::copy_options::skip_existing);
    for (const char* png : {"floor_tiles.png", "panel_stripes.png", "panel_grid.png"})
        fs::copy_file(kRoomDir / png, dir.path / png, fs::copy_options::skip_existing);
    edit(j);
    const fs::path out = dir.path / name;
    std::ofstream(out) << j.dump();
    return out;
}

// A float accessor over a new buffer file holding `values` (comps per element).
int addFloats(const test::TempDir& dir, nlohmann::json& j, const std::vector<float>& values,
              int comps) {
    const std::string file = "extra" + std::to_string(j["buffers"].size()) + ".bin";
    std::ofstream(dir.path / file, std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()),
               std::streamsize(values.size() * sizeof(float)));
    j["buffers"].push_back({{"uri", file}, {"byteLength", values.size() * sizeof(float)}});
    j["bufferViews"].push_back(
        {{"buffer", j["buffers"].size() - 1}, {"byteLength", values.size() * sizeof(float)}});
    const char* type = comps == 1 ? "SCALAR" : comps == 3 ? "VEC3" : "VEC4";
    j["accessors"].push_back({{"bufferView", j["bufferViews"].size() - 1},
                              {"componentType", 5126},
                              {"count", values.size() / std::size_t(comps)},
                              {"type", type}});
    return int(j["accessors"].size()) - 1;
}

TEST(GltfAnimation, BadChannelsAreRefusedNamingTheField) {
    test::TempDir dir("animation");
    struct Case {
        const char* name;
        std::function<void(nlohmann::json&)> edit;
        const char* expected; // in the message
    };
    const std::vector<Case> cases = {
        {"interpolation.gltf",
         [](nlohmann::json& j) { j["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH"; },
         "animations[0].samplers[0].interpolation"},
        {"node.gltf",
         [](nlohmann::json& j) { j["animations"][0]["channels"][0]["target"]["node"] = 99; },
         "animations[0].channels[0].target.node"},
        {"sampler.gltf",
         [](nlohmann::json& j) { j["animations"][0]["channels"][1]["sampler"] = 7; },
         "animations[0].channels[1].sampler"},
        {"twice.gltf",
         [](nlohmann::json& j) {
             j["animations"][0]["channels"].push_back(j["animations"][0]["channels"][0]);
         },
         "same node and path"},
        {"times.gltf",
         [&](nlohmann::json& j) {
             j["animations"][0]["samplers"][0]["input"] =
                 addFloats(dir, j, {0.f, 1.f, 1.f, 3.f, 4.f}, 1);
         },
         "increase strictly"},
        {"count.gltf",
         [&](nlohmann::json& j) {
             j["animations"][0]["samplers"][0]["input"] = addFloats(dir, j, {0.f, 1.f, 2.f}, 1);
         },
         "expected 3 values"},
        {"zero.gltf",
         [&](nlohmann::json& j) {
             std::vector<float> q(20, 0.f);
             for (int k = 0; k < 5; ++k)
                 q[std::size_t(4 * k + 3)] = k == 2 ? 0.f : 1.f; // key 2 is all zero
             j["animations"][0]["samplers"][1]["output"] = addFloats(dir, j, q, 4);
         },
         "rotation key 2 is zero"},
        {"type.gltf",
         [](nlohmann::json& j) {
             j["animations"][0]["samplers"][0]["input"] =
                 j["animations"][0]["samplers"][0]["output"];
         },
         "expected SCALAR"},
    };
    for (const Case& c : cases) {
        const fs::path p = editedRoom(dir, c.name, c.edit);
        expectLoadError(p, c.expected);
    }
}

} // namespace
