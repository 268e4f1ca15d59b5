#include "sandbox/lib/render/reflection_scene.h"
#include "assetcooker/lib/scene/walk_amplitude.h"

#include "components/reflection_probe/system/reflection_probe.h"
#include "components/reflection_probe/system/reflector_roughness.h"
#include "components/reflection_probe/walk_path.h"

#include "engine/scene/mesh_bounds.h"

#include <algorithm>
#include <utility>

namespace specula {

std::string defaultScenePath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/room/room.gltf";
}
std::string defaultSkyPath() {
    return std::string(SPECULA_SOURCE_ROOT) + "/assets/scenes/env/field.jpg";
}

namespace {
thread_local const AddedReflectorsScope* innermostScope = nullptr;
} // namespace

AddedReflectorsScope::AddedReflectorsScope(std::vector<AddedReflector> added)
    : added_(std::move(added)), outer_(innermostScope) {
    innermostScope = this;
}

AddedReflectorsScope::~AddedReflectorsScope() {
    innermostScope = outer_;
}

const std::vector<AddedReflector>& AddedReflectorsScope::current() {
    static const std::vector<AddedReflector> none;
    return innermostScope ? innermostScope->added_ : none;
}

ReflectionScene::ReflectionScene(const std::string& gltfPath, const std::string& skyPath)
    : ReflectionScene(gltfPath, skyPath, AddedReflectorsScope::current()) {}

ReflectionScene::ReflectionScene(const std::string& gltfPath, const std::string& skyPath,
                                 const std::vector<AddedReflector>& added)
    : scene_(gltfPath, skyPath, added), reflectors_(scene_) {}

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
    return specula::walkAmplitude(scene_, reflectorOffset());
}

CameraView ReflectionScene::camera(int width, int height) const {
    return sceneCameraView(scene_, width, height);
}

CameraView ReflectionScene::orbitCamera(int width, int height, float angle, float distance,
                                        float heightAbove) const {
    return orbitCameraView(probeCentre(), width, height, angle, distance, heightAbove);
}

void ReflectionScene::setReflectorOffset(glm::vec3 offset) {
    reflectors_.setOffset(scene_.registry, offset);
}

glm::vec3 ReflectionScene::reflectorPosition() const {
    return reflectors_.roots().empty() ? probeCentre()
                                       : reflectors_.roots().front().second + reflectorOffset();
}

void ReflectionScene::setReflectorRoughness(float roughness) {
    scene_.registry.view<Reflector>().each(
        [&](ecs::Entity, Reflector& r) { r.roughness = roughness; });
}

GroundTruthImage ReflectionScene::groundTruth(const CameraView& camera, bool environmentOnly) {
    TraceOptions o = groundTruthOptions(scene_, environmentOnly);
    bool rough = false;
    scene_.registry.view<Reflector>().each(
        [&](ecs::Entity, Reflector& r) { rough = rough || r.roughness > 0.f; });
    // Mirrors only: the mirror path as before, bit for bit, without a call per hit.
    if (rough) {
        const ecs::Registry& registry = scene_.registry;
        o.mirrorRoughness = [&registry](ecs::Entity e, glm::vec2 uv) {
            const Reflector* r = registry.find<Reflector>(e);
            return r ? roughnessAt(r->roughness, r->roughnessMap.get(), uv) : 0.f;
        };
        o.glossySamples = std::max(1, glossySamples_);
    }
    return GroundTruthTracer(scene_.registry, o).render(camera);
}

} // namespace specula
