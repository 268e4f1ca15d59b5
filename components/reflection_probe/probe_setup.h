#pragma once
// What a game does to use reflection probes in a glTF scene, without the cooker or the
// sandbox: open the scene with its Specula markup and sky, turn the markup into components
// (a ReflectionProbe entity, a Reflector on every reflector mesh), and read what a loader
// needs of a cooked manifest before it loads the asset. Also what the sandbox and the
// tests share on such a scene: edit the probe's settings, camera views, reflector offsets,
// the ray-traced ground truth.
#include "components/reflection_probe/reflection_probe.h"
#include "components/reflection_probe/scene_markup.h"
#include "engine/ecs/registry.h"
#include "engine/image/image.h"
#include "engine/math/camera.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/gltf_loader.h"

#include <string>
#include <utility>
#include <vector>

namespace specula {

// A glTF scene opened for probe work: loaded, world transforms up to date, markup read, sky
// panorama loaded (empty skyPath: a black sky). Throws Error naming the file on bad input.
struct ProbeScene {
    ProbeScene(const std::string& gltfPath, const std::string& skyPath);

    std::string path;
    std::string skyPath; // as given (empty: a black sky)
    ecs::Registry registry;
    LoadedScene loaded;
    SceneMarkup markup;
    Image sky;
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
// sceneCameraView: the scene's first camera node, else the probe centre (markupProbeCentre)
// from 3.5 m, 0.6 m above.
CameraView orbitCameraView(glm::vec3 centre, int width, int height, float angleRadians,
                           float distance, float heightAbove);
CameraView sceneCameraView(const ProbeScene& scene, int width, int height);

// The walk's camera orbit about the probe centre: the scene camera's (sceneCameraView) angle
// about +Y (0: from +Z), horizontal distance (at least 0.5 m) and height above the centre.
struct CameraOrbit {
    float angle = 0.f, distance = 3.5f, height = 0.6f;
};
CameraOrbit sceneCameraOrbit(const ProbeScene& scene);
// The camera of walk frame t in [0, 1) (specula-sandbox walk, the PEM viewpoint parameter):
// the scene camera's orbit swung by 0.4 sin(2 pi t) radians (+-23 degrees) about its angle.
CameraView walkOrbitCameraView(const ProbeScene& scene, int width, int height, float t);

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
    // flavour that keeps no copy (a PEM's maps hold the sky already); empty when absent.
    std::string skySource;
};
// Throws Error naming the manifest and the field when it is no Specula probe manifest of
// this format version.
CookedProbeFacts readCookedProbeFacts(const std::string& manifestPath);

} // namespace specula
