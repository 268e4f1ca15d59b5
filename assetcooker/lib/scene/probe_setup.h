#pragma once
// What a game does to use reflection probes in a glTF scene, without the cooker or the
// sandbox: open the scene with its Specula markup and sky, turn the markup into components
// (a ReflectionProbe entity, a Reflector on every reflector mesh), and read what a loader
// needs of a cooked manifest before it loads the asset. Also what the sandbox and the
// tests share on such a scene: edit the probe's settings, camera views, reflector offsets,
// the ray-traced ground truth.
#include "assetcooker/lib/scene/added_reflector.h"
#include "assetcooker/lib/scene/scene_markup.h"
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/system/reflection_probe.h"
#include "engine/core/error.h"
#include "engine/ecs/registry.h"
#include "engine/image/image.h"
#include "engine/math/camera.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/gltf_loader.h"

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace specula {

// A camera orbit about the probe centre: the angle about +Y (0: from +Z), the horizontal
// distance and the height above the centre.
struct CameraOrbit {
    float angle = 0.f, distance = 3.5f, height = 0.6f;
};

// The default camera of a scene without a camera node (see sceneCameraView), searched for
// once on first use and kept (an orbit about the probe centre, or the error saying none was
// found). Thread-safe; forget() makes the next use search again (addReflector calls it).
class DefaultViewCache {
public:
    DefaultViewCache() : state_(std::make_unique<State>()) {}
    // The kept orbit, else search()'s (its Error is kept and thrown again too).
    CameraOrbit get(const std::function<CameraOrbit()>& search) const;
    void forget();

private:
    struct State {
        std::mutex mutex;
        std::optional<CameraOrbit> orbit;
        std::optional<Error> error;
    };
    std::unique_ptr<State> state_;
};

// A glTF scene opened for probe work: loaded, world transforms up to date, markup read, the
// `added` test mirrors added to it (addReflector), sky panorama loaded (empty skyPath: a
// black sky). Throws Error naming the file on bad input.
struct ProbeScene {
    ProbeScene(const std::string& gltfPath, const std::string& skyPath,
               const std::vector<AddedReflector>& added = {});

    std::string path;
    std::string skyPath; // as given (empty: a black sky)
    ecs::Registry registry;
    LoadedScene loaded;
    SceneMarkup markup;
    Image sky;
    DefaultViewCache defaultView; // sceneCameraView's search, when the scene has no camera
};

// Creates an entity holding `probe` (named "reflection_probe") and gives every reflector
// mesh of `markup` a Reflector pointing at it. `previous`, when not null, is the probe
// entity this one replaces: it is destroyed first. Returns the new probe entity.
ecs::Entity attachProbeComponents(ecs::Registry& registry, const SceneMarkup& markup,
                                  const ReflectionProbe& probe,
                                  ecs::Entity previous = ecs::kNullEntity);

// Points `probe` at `asset` with the flavour's `settings`: edited in place when the entity
// already holds settings of this flavour (the probe system sees an edit), else a new probe
// entity replaces it (attachProbeComponents) with the settings emplaced. Returns the probe
// entity.
template <typename Settings>
ecs::Entity setProbeComponents(ecs::Registry& registry, const SceneMarkup& markup,
                               ecs::Entity probe, const std::string& asset,
                               const Settings& settings) {
    if (probe.isNull() || !registry.has<Settings>(probe)) {
        probe = attachProbeComponents(registry, markup, ReflectionProbe{asset}, probe);
        registry.emplace<Settings>(probe, settings);
        return probe;
    }
    registry.get<ReflectionProbe>(probe).asset = asset;
    registry.get<Settings>(probe) = settings;
    return probe;
}

// Views of an opened scene. orbitCameraView: `centre` seen from `distance` m away at
// `angleRadians` about +Y (0: from +Z) and `heightAbove` m above it, 50 degree field.
// sceneCameraView: the scene's first camera node; else, when the scene has reflectors, the
// probe centre (markupProbeCentre; the centre of the reflectors' bounds unless a probe node
// says otherwise) seen from the first free viewpoint (defaultViewpointOrbit); else (nothing
// to see) the probe centre from 3.5 m, 0.6 m above.
CameraView orbitCameraView(glm::vec3 centre, int width, int height, float angleRadians,
                           float distance, float heightAbove);
CameraView sceneCameraView(const ProbeScene& scene, int width, int height);

// How the default camera is searched for, in a fixed order (deterministic): first the old
// default (from +Z, 3.5 m, 0.6 m above the centre), then horizontal distances of
// {3, 2, 4, 1.5, 6} x the reflectors' radius (half their bounds' diagonal; at least 0.8 m),
// heights of {0.17, 0.45, 0, -0.25} x that distance, and 12 angles about +Y from +Z
// alternating sides (0, +30, -30, ... 180 degrees). With Embree over every mesh:
//  - a viewpoint stands free when, of kFreeSpaceRays rays spread over the sphere, none hits a
//    surface nearer than kClearance m and at most kMaxBackFaceHits first hit the back of a
//    single-sided surface (the inside of a solid, the outside of a room's walls), and no
//    environment surface lies between it and the centre;
//  - a candidate is valid when it stands free and at least kMinMirrorShare of a 48x36
//    image's primary rays first hit a mirror.
// The first valid candidate is taken whose walk swing (+-kWalkSwing and half that, as
// walkOrbitCameraView swings it) stands free too and which is no more open to the sky (the
// share of its rays that meet nothing) than the centre is (of rays meeting no environment
// surface) plus kMaxExtraOpenness: inside the reflectors' room, not outside looking in
// through a window. Failing that, the first valid one whose swing stands free; then the
// first valid one. Throws Error (the scene's file, field "camera") when none is valid,
// saying how to give a viewpoint: a camera node in the glTF, or a reflector in free space
// (--add-reflector). The scene's reflectors must be where the camera should see them.
struct DefaultViewpointRules {
    static constexpr int kFreeSpaceRays = 128;
    static constexpr int kMaxBackFaceHits = 2;
    static constexpr float kClearance = 0.1f;
    static constexpr float kMinMirrorShare = 0.01f;
    static constexpr float kMaxExtraOpenness = 0.2f;
    static constexpr float kWalkSwing = 0.4f; // radians (+-23 degrees)
};
CameraOrbit defaultViewpointOrbit(const ProbeScene& scene);

// The walk's camera orbit about the probe centre: the scene camera's (sceneCameraView) angle
// about +Y (0: from +Z), horizontal distance (at least 0.5 m) and height above the centre.
CameraOrbit sceneCameraOrbit(const ProbeScene& scene);
// The camera of walk frame t in [0, 1) (specula-sandbox walk, the PEM viewpoint parameter):
// the scene camera's orbit swung by kWalkSwing sin(2 pi t) radians (+-23 degrees) about its
// angle.
CameraView walkOrbitCameraView(const ProbeScene& scene, int width, int height, float t);

// The scene camera (sceneCameraView's node) at fraction t in [0, 1] of its animation's span
// (the glTF animation of the camera node and its ancestors, NodeAnimation; 0 the first key,
// 1 the last): the PEM's "camera" path. An open path, unlike the walk's loops. Throws Error
// naming the scene's file and "path" when the scene has no camera node or nothing moves it.
CameraView cameraPathView(const ProbeScene& scene, int width, int height, float t);
// Whether cameraPathView has a path to follow.
bool sceneCameraMoves(const ProbeScene& scene);

// The reflector nodes of the markup (found by name) with their authored translations, to
// move them all by one world-space offset (the translation is the parent's space, which is
// world space for root nodes: the reflectors of our scenes).
class ReflectorRoots {
public:
    explicit ReflectorRoots(const ProbeScene& scene);
    // Moves every root to authored + offset and updates the world transforms.
    void setOffset(ecs::Registry& registry, glm::vec3 offset);
    glm::vec3 offset() const { return offset_; }
    // (entity, authored translation), in markup order.
    const std::vector<std::pair<ecs::Entity, glm::vec3>>& roots() const { return roots_; }

private:
    std::vector<std::pair<ecs::Entity, glm::vec3>> roots_;
    glm::vec3 offset_{0.f};
};

// The Embree ground truth of the scene as it stands (the markup's mirrors, its sky).
// environmentOnly: reflected rays see only the environment, one bounce (what a probe
// represents); else up to four bounces.
GroundTruthImage traceGroundTruth(ProbeScene& scene, const CameraView& camera,
                                  bool environmentOnly);
// The tracer options traceGroundTruth uses (the markup's mirrors, the sky, the bounces).
TraceOptions groundTruthOptions(const ProbeScene& scene, bool environmentOnly);

// What a loader needs of a cooked probe before loading it, from one read of its manifest:
// the flavour that picks the loader, the scene it was baked from and the sky file. The
// asset itself (fields, files, checksums) is validated when it is loaded.
struct CookedProbeFacts {
    std::string flavour; // "distance", "lightfield"
    std::string source;  // the "source" member as written (a path; empty when absent)
    std::string skyFile; // the sky image beside the manifest (a path; empty when none)
    // "sky_source": the sky the bake used, as it was given (a path, like "source"), for a
    // flavour that keeps no copy (a PEM's maps hold the sky already); empty for a black sky.
    // skySourceGiven: the manifest has the field (older PEM manifests do not).
    std::string skySource;
    bool skySourceGiven = false;
    ProbeInputs inputs; // "inputs": what the cooker baked it from (not recorded: empty)
};
// Throws Error naming the manifest and the field when it is no Specula probe manifest of
// this format version.
CookedProbeFacts readCookedProbeFacts(const std::string& manifestPath);

} // namespace specula
