#include "probe_setup.h"

#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/image/image_io.h"
#include "engine/scene/components.h"
#include "engine/scene/transform_system.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace specula {

ProbeScene::ProbeScene(const std::string& gltfPath, const std::string& skyPath)
    : path(gltfPath), skyPath(skyPath) {
    loaded = loadGltf(gltfPath, registry);
    updateWorldTransforms(registry);
    markup = readSceneMarkup(registry, loaded, gltfPath);
    if (!skyPath.empty()) sky = readImage(skyPath);
}

ecs::Entity attachProbeComponents(ecs::Registry& registry, const SceneMarkup& markup,
                                  const ReflectionProbe& probe, ecs::Entity previous) {
    if (!previous.isNull()) registry.destroy(previous);
    const ecs::Entity e = registry.create();
    registry.emplace<Name>(e, Name{"reflection_probe"});
    registry.emplace<ReflectionProbe>(e, probe);
    for (const ReflectorMarkup& r : markup.reflectors)
        for (ecs::Entity mesh : r.meshes)
            registry.emplace<Reflector>(mesh, Reflector{e, r.f0});
    return e;
}

CameraView orbitCameraView(glm::vec3 centre, int width, int height, float angle, float distance,
                           float heightAbove) {
    const glm::vec3 eye =
        centre + glm::vec3(distance * std::sin(angle), heightAbove, distance * std::cos(angle));
    return CameraView::lookAt(eye, centre, glm::vec3(0, 1, 0), glm::radians(50.f), width, height);
}

CameraView sceneCameraView(const ProbeScene& scene, int width, int height) {
    for (ecs::Entity e : scene.loaded.entities) {
        const Camera* cam = scene.registry.find<Camera>(e);
        const Transform* t = scene.registry.find<Transform>(e);
        if (!cam || !t) continue;
        CameraView v;
        // The camera looks down its local -Z; the view matrix is the inverse of its world.
        v.view = glm::inverse(t->world);
        v.proj = glm::perspective(cam->yfov, float(width) / float(height), cam->znear, cam->zfar);
        v.width = width;
        v.height = height;
        return v;
    }
    return orbitCameraView(markupProbeCentre(scene.registry, scene.markup, scene.loaded), width,
                           height, 0.f, 3.5f, 0.6f);
}

CameraOrbit sceneCameraOrbit(const ProbeScene& scene) {
    const glm::vec3 c = markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    const glm::vec3 e = sceneCameraView(scene, 64, 48).eye() - c;
    return {std::atan2(e.x, e.z), std::max(0.5f, std::hypot(e.x, e.z)), e.y};
}

CameraView walkOrbitCameraView(const ProbeScene& scene, int width, int height, float t) {
    const CameraOrbit o = sceneCameraOrbit(scene);
    return orbitCameraView(markupProbeCentre(scene.registry, scene.markup, scene.loaded), width,
                           height, o.angle + 0.4f * std::sin(glm::two_pi<float>() * t), o.distance,
                           o.height);
}

ReflectorRoots::ReflectorRoots(const ProbeScene& scene) {
    for (const ReflectorMarkup& r : scene.markup.reflectors)
        for (ecs::Entity e : scene.loaded.entities)
            if (const Name* n = scene.registry.find<Name>(e); n && n->value == r.node)
                if (const Transform* t = scene.registry.find<Transform>(e))
                    roots_.emplace_back(e, t->translation);
}

void ReflectorRoots::setOffset(ecs::Registry& registry, glm::vec3 offset) {
    offset_ = offset;
    for (const auto& [e, authored] : roots_)
        registry.get<Transform>(e).translation = authored + offset;
    updateWorldTransforms(registry);
}

TraceOptions groundTruthOptions(const ProbeScene& scene, bool environmentOnly) {
    TraceOptions o;
    o.environmentOnly = environmentOnly;
    o.mirrors = scene.markup.mirrorEntities;
    o.sky = scene.sky.empty() ? nullptr : &scene.sky;
    // Probes reflect at most once; the full ground truth follows a few bounces.
    o.maxBounces = environmentOnly ? 1 : 4;
    return o;
}

GroundTruthImage traceGroundTruth(ProbeScene& scene, const CameraView& camera,
                                  bool environmentOnly) {
    return GroundTruthTracer(scene.registry, groundTruthOptions(scene, environmentOnly))
        .render(camera);
}

CookedProbeFacts readCookedProbeFacts(const std::string& manifestPath) {
    const nlohmann::json m = parseManifestJson(readManifestText(manifestPath), manifestPath);
    const ManifestFields r{manifestPath};
    CookedProbeFacts f;
    f.flavour = r.probeFlavour(m, kProbeFormatVersion);
    if (m.contains("source")) f.source = r.string(m, "source", "");
    if (m.contains("sky_source")) f.skySource = r.string(m, "sky_source", "");
    if (m.contains("sky"))
        f.skyFile =
            r.fileInFolder(m["sky"], "sky.", std::filesystem::path(manifestPath).parent_path());
    return f;
}

} // namespace specula
