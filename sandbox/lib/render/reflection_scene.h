#pragma once
// A glTF scene set up for reflection work: loaded into a registry, its Specula markup read,
// the sky panorama loaded, the camera found, and helpers to attach a probe, move the
// reflectors and trace the ground truth. Shared by specula-sandbox and the tests.
#include "assetcooker/lib/scene/probe_setup.h"
#include "assetcooker/lib/scene/walk_amplitude.h"
#include "engine/math/camera.h"
#include "engine/raytrace/ground_truth.h"

#include <string>
#include <vector>

namespace specula {

std::string defaultScenePath(); // assets/room/room.gltf in the source tree
std::string defaultSkyPath();   // assets/scenes/env/field.jpg

// The test mirrors (specula-sandbox --add-reflector) every ReflectionScene opened on this
// thread without its own list gets while the scope lives: walk and bench set it once, and
// each place that opens their scene (the bake in resolveProbeSource, the headless and the
// window walk, the bench) opens it with them. Scopes nest; the innermost wins.
class AddedReflectorsScope {
public:
    explicit AddedReflectorsScope(std::vector<AddedReflector> added);
    ~AddedReflectorsScope();
    AddedReflectorsScope(const AddedReflectorsScope&) = delete;
    AddedReflectorsScope& operator=(const AddedReflectorsScope&) = delete;
    // The innermost scope's list; empty outside any.
    static const std::vector<AddedReflector>& current();

private:
    std::vector<AddedReflector> added_;
    const AddedReflectorsScope* outer_;
};

class ReflectionScene {
public:
    // Throws Error naming the file on bad input. An empty skyPath means a black sky. The
    // scene gets the reflectors of the current AddedReflectorsScope (none outside one).
    ReflectionScene(const std::string& gltfPath, const std::string& skyPath);
    // The scene with `added` (addReflector), whatever the current scope says.
    ReflectionScene(const std::string& gltfPath, const std::string& skyPath,
                    const std::vector<AddedReflector>& added);

    ecs::Registry& registry() { return scene_.registry; }
    const LoadedScene& loaded() const { return scene_.loaded; }
    const SceneMarkup& markup() const { return scene_.markup; }
    const Image& sky() const { return scene_.sky; }
    const std::string& path() const { return scene_.path; }
    // The opened scene itself, for the cooking API (cookProbe) to bake from.
    ProbeScene& probeScene() { return scene_; }
    const ProbeScene& probeScene() const { return scene_; }

    // The probe position: the first `specula_probe` node, else the centre of the
    // reflectors' bounds, else the scene's centre.
    glm::vec3 probeCentre() const;
    // Side of the cubic cell the reflectors move in (`cell_size` of the probe markup, else
    // 1.5 m).
    float cellSize() const;
    // Largest distance from the probe centre to any reflector vertex (with the cell).
    float reflectorReach() const;
    // How far the reflectors may move from where they were authored on every axis and stay
    // inside the cell: at most a fifth of the cell, never more than the room they have.
    float walkAmplitude() const;

    // The scene's first camera node, else a free viewpoint that sees the reflectors
    // (sceneCameraView; throws Error when there is none).
    CameraView camera(int width, int height) const;
    CameraView orbitCamera(int width, int height, float angleRadians, float distance,
                           float height_) const;

    // Creates (or replaces) the probe entity: a ReflectionProbe on `asset` with the flavour's
    // settings component, and a Reflector on every reflector mesh (attachProbeComponents).
    template <typename Settings>
    ecs::Entity attachProbe(const std::string& asset, const Settings& settings) {
        probe_ =
            attachProbeComponents(scene_.registry, scene_.markup, ReflectionProbe{asset}, probe_);
        scene_.registry.emplace<Settings>(probe_, settings);
        return probe_;
    }
    ecs::Entity probeEntity() const { return probe_; }
    // Edits the probe in place when it holds settings of this flavour (the system sees an
    // edit); otherwise attaches a new one (setProbeComponents).
    template <typename Settings> void setProbe(const std::string& asset, const Settings& settings) {
        probe_ = setProbeComponents(scene_.registry, scene_.markup, probe_, asset, settings);
    }

    // Moves every reflector node to its authored position + offset (world space).
    void setReflectorOffset(glm::vec3 offset);
    glm::vec3 reflectorOffset() const { return reflectors_.offset(); }
    // World position of the first reflector node (authored + offset); the probe centre when
    // the scene has no reflector.
    glm::vec3 reflectorPosition() const;

    bool isMirror(ecs::Entity e) const { return scene_.markup.mirrorEntities.count(e) > 0; }

    // Every Reflector component's roughness factor (GGX, alpha = r^2; a roughness map keeps
    // multiplying it per pixel): what the probe stores draw with.
    void setReflectorRoughness(float roughness);
    // GGX samples a pixel of the truth where a reflector is rough (at least 1).
    void setGlossyTruthSamples(int samples) { glossySamples_ = samples; }

    // Ray-traced ground truth of the current state. environmentOnly: reflected rays see
    // only the environment (what a probe represents). A reflector is as rough as it is
    // drawn: its Reflector component's roughness (times its map at the hit), GGX-sampled.
    GroundTruthImage groundTruth(const CameraView& camera, bool environmentOnly);

private:
    ProbeScene scene_;
    ecs::Entity probe_ = ecs::kNullEntity;
    ReflectorRoots reflectors_;
    int glossySamples_ = TraceOptions{}.glossySamples;
};

} // namespace specula
