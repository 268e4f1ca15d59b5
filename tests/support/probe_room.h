#pragma once
// The probe tests' scene and renderer, from the components, the engine and the cooker only
// (no sandbox code). ProbeRoom: a glTF scene opened with its sky (the default room), a
// probe pointed at a cooked asset, the reflectors moved inside the cell, the Embree ground
// truth. RoomRenderer: the environment through SceneRenderer and the reflectors through
// ReflectionProbeSystem into an offscreen float target; needs a current GL context.
#include "assetcooker/lib/scene/probe_setup.h"
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/system/reflection_probe_system.h"
#include "engine/gpu/render_target.h"
#include "engine/render/scene_renderer.h"

#include <string>

namespace specula::test {

inline const std::string kRoomScene = SPECULA_SOURCE_DIR "/assets/room/room.gltf";
inline const std::string kRoomSky = SPECULA_SOURCE_DIR "/assets/scenes/env/field.jpg";

class ProbeRoom {
public:
    // Throws Error naming the file on bad input. An empty skyPath means a black sky.
    explicit ProbeRoom(const std::string& gltfPath = kRoomScene,
                       const std::string& skyPath = kRoomSky)
        : scene_(gltfPath, skyPath), reflectors_(scene_) {}

    ecs::Registry& registry() { return scene_.registry; }
    const SceneMarkup& markup() const { return scene_.markup; }
    const Image& sky() const { return scene_.sky; }
    const std::string& path() const { return scene_.path; }
    // The opened scene, for the cooking API (cookProbe) to bake from.
    ProbeScene& probeScene() { return scene_; }

    // The markup's probe position, cell side and reflector reach (scene_markup.h).
    glm::vec3 probeCentre() const {
        return markupProbeCentre(scene_.registry, scene_.markup, scene_.loaded);
    }
    float cellSize() const { return markupCellSize(scene_.markup); }
    float reflectorReach() const {
        return markupReflectorReach(scene_.registry, scene_.markup, probeCentre(), cellSize());
    }

    // The scene's first camera node, else the probe centre from 3.5 m (sceneCameraView).
    CameraView camera(int width, int height) const {
        return sceneCameraView(scene_, width, height);
    }
    CameraView orbitCamera(int width, int height, float angle, float distance,
                           float heightAbove) const {
        return orbitCameraView(probeCentre(), width, height, angle, distance, heightAbove);
    }

    // Points the probe at `asset` with the flavour's settings: an edit in place when the
    // probe holds settings of this flavour, else a new probe entity (setProbeComponents).
    template <typename Settings> void setProbe(const std::string& asset, const Settings& settings) {
        probe_ = setProbeComponents(scene_.registry, scene_.markup, probe_, asset, settings);
    }
    ecs::Entity probeEntity() const { return probe_; }

    // Moves every reflector node to its authored position + offset (world space).
    void setReflectorOffset(glm::vec3 offset) { reflectors_.setOffset(scene_.registry, offset); }

    bool isMirror(ecs::Entity e) const { return scene_.markup.mirrorEntities.count(e) > 0; }

    // Ray-traced ground truth of the current state. environmentOnly: reflected rays see
    // only the environment (what a probe represents).
    GroundTruthImage groundTruth(const CameraView& camera, bool environmentOnly) {
        return traceGroundTruth(scene_, camera, environmentOnly);
    }

private:
    ProbeScene scene_;
    ReflectorRoots reflectors_;
    ecs::Entity probe_ = ecs::kNullEntity;
};

class RoomRenderer {
public:
    RoomRenderer(ProbeRoom& room, int width, int height) : room_(room), target_(width, height) {
        if (!room.sky().empty()) scene_.setSky(room.sky());
    }

    // The current state; output 0 = colour, 1/2 = the reflector pixels' probe-local
    // position / reflected direction (the CPU twin's inputs; other pixels hold the scene).
    Image render(const CameraView& camera, int output = 0) {
        ecs::Registry& reg = room_.registry();
        scene_.sync(reg);
        probes_.sync(reg);
        scene_.render(camera, target_, [&](ecs::Entity e) { return reg.has<Reflector>(e); });
        probes_.render(reg, camera, scene_, target_, output);
        return target_.readback();
    }
    // Environment and sky only, the mirrors skipped (rasteriser-vs-tracer checks).
    Image renderEnvironment(const CameraView& camera) {
        scene_.sync(room_.registry());
        scene_.render(camera, target_, [&](ecs::Entity e) { return room_.isMirror(e); });
        return target_.readback();
    }

    ReflectionProbeSystem& probes() { return probes_; }
    const ProbeFrameStats& stats() const { return probes_.stats(); }

private:
    ProbeRoom& room_;
    SceneRenderer scene_;
    ReflectionProbeSystem probes_;
    gpu::RenderTarget target_;
};

} // namespace specula::test
