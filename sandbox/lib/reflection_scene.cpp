#include "reflection_scene.h"

#include "engine/core/error.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"
#include "engine/scene/transform_system.h"

#include <algorithm>

namespace specula {

std::string defaultScenePath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/room/room.gltf";
}
std::string defaultSkyPath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/scenes/env/field.jpg";
}

ReflectionScene::ReflectionScene(const std::string& gltfPath, const std::string& skyPath)
    : scene_(gltfPath, skyPath) {
    // Reflector roots: the nodes carrying the markup, found by name.
    for (const ReflectorMarkup& r : scene_.markup.reflectors)
        for (ecs::Entity e : scene_.loaded.entities)
            if (const Name* n = scene_.registry.find<Name>(e); n && n->value == r.node)
                reflectorRoots_.emplace_back(e, scene_.registry.get<Transform>(e).translation);
}

glm::vec3 ReflectionScene::probeCentre() const {
    return markupProbeCentre(scene_.registry, scene_.markup, scene_.loaded);
}

float ReflectionScene::cellSize() const {
    return markupCellSize(scene_.markup);
}

float ReflectionScene::reflectorReach() const {
    return markupReflectorReach(scene_.registry, scene_.markup, probeCentre(), cellSize());
}

float ReflectionScene::walkAmplitude() const {
    const float half = 0.5f * cellSize();
    const Aabb cell = Aabb::cube(probeCentre(), half);
    float slack = half;
    // Room to the cell's faces of each mirror at its authored position (the current offset
    // taken away).
    for (ecs::Entity e : scene_.markup.mirrorEntities)
        slack = std::min(slack,
                         -meshWorldBounds(scene_.registry, e).translated(-offset_).overhang(cell));
    return std::clamp(slack, 0.f, 0.2f * cellSize());
}

CameraView ReflectionScene::camera(int width, int height) const {
    for (ecs::Entity e : scene_.loaded.entities) {
        const Camera* cam = scene_.registry.find<Camera>(e);
        const Transform* t = scene_.registry.find<Transform>(e);
        if (!cam || !t) continue;
        const glm::mat4 world = t->world;
        CameraView v;
        // The camera looks down its local -Z; the view matrix is the inverse of its world.
        v.view = glm::inverse(world);
        v.proj = glm::perspective(cam->yfov, float(width) / float(height), cam->znear, cam->zfar);
        v.width = width;
        v.height = height;
        return v;
    }
    return orbitCamera(width, height, 0.f, 3.5f, 0.6f);
}

CameraView ReflectionScene::orbitCamera(int width, int height, float angle, float distance,
                                        float heightAbove) const {
    const glm::vec3 c = probeCentre();
    const glm::vec3 eye =
        c + glm::vec3(distance * std::sin(angle), heightAbove, distance * std::cos(angle));
    return CameraView::lookAt(eye, c, glm::vec3(0, 1, 0), glm::radians(50.f), width, height);
}

void ReflectionScene::setReflectorOffset(glm::vec3 offset) {
    offset_ = offset;
    for (auto& [e, authored] : reflectorRoots_) {
        Transform& t = scene_.registry.get<Transform>(e);
        // The authored translation is in the parent's space; offsets are world space, which is
        // the same for root nodes (the reflectors of our scenes).
        t.translation = authored + offset;
    }
    updateWorldTransforms(scene_.registry);
}

glm::vec3 ReflectionScene::reflectorPosition() const {
    return reflectorRoots_.empty() ? probeCentre() : reflectorRoots_.front().second + offset_;
}

GroundTruthImage ReflectionScene::groundTruth(const CameraView& camera, bool environmentOnly) {
    TraceOptions o;
    o.environmentOnly = environmentOnly;
    o.mirrors = scene_.markup.mirrorEntities;
    o.sky = scene_.sky.empty() ? nullptr : &scene_.sky;
    // Probes reflect at most once; the full ground truth follows a few bounces.
    o.maxBounces = environmentOnly ? 1 : 4;
    GroundTruthTracer tracer(scene_.registry, std::move(o));
    return tracer.render(camera);
}

} // namespace specula
