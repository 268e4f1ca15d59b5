#include "probe_setup.h"

#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/manifest_fields.h"
#include "engine/core/error.h"
#include "engine/image/ktx2.h"
#include "engine/image_io/image_io.h"
#include "engine/raytrace/embree_scene.h"
#include "engine/scene/animation.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"
#include "engine/scene/transform_system.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace specula {

CameraOrbit DefaultViewCache::get(const std::function<CameraOrbit()>& search) const {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    if (state_->orbit) return *state_->orbit;
    if (state_->error) throw *state_->error;
    try {
        state_->orbit = search();
    } catch (const Error& e) {
        state_->error = e;
        throw;
    }
    return *state_->orbit;
}

void DefaultViewCache::forget() {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    state_->orbit.reset();
    state_->error.reset();
}

ProbeScene::ProbeScene(const std::string& gltfPath, const std::string& skyPath,
                       const std::vector<AddedReflector>& added)
    : path(gltfPath), skyPath(skyPath) {
    loaded = loadGltf(gltfPath, registry);
    updateWorldTransforms(registry);
    markup = readSceneMarkup(registry, loaded, gltfPath);
    for (const AddedReflector& r : added)
        addReflector(*this, r);
    // A cooked probe's own sky is KTX2 (the sandbox replays a probe with it); a user's is
    // any image file OpenImageIO reads.
    if (!skyPath.empty())
        sky = std::filesystem::path(skyPath).extension() == ".ktx2" ? readKtx2Image(skyPath)
                                                                    : readImage(skyPath);
}

ecs::Entity attachProbeComponents(ecs::Registry& registry, const SceneMarkup& markup,
                                  const ReflectionProbe& probe, ecs::Entity previous) {
    if (!previous.isNull()) registry.destroy(previous);
    const ecs::Entity e = registry.create();
    registry.emplace<Name>(e, Name{"reflection_probe"});
    registry.emplace<ReflectionProbe>(e, probe);
    for (const ReflectorMarkup& r : markup.reflectors)
        for (ecs::Entity mesh : r.meshes)
            registry.emplace<Reflector>(mesh, Reflector{e, r.f0, r.roughness, r.roughnessMap});
    return e;
}

CameraView orbitCameraView(glm::vec3 centre, int width, int height, float angle, float distance,
                           float heightAbove) {
    const glm::vec3 eye =
        centre + glm::vec3(distance * std::sin(angle), heightAbove, distance * std::cos(angle));
    return CameraView::lookAt(eye, centre, glm::vec3(0, 1, 0), glm::radians(50.f), width, height);
}

namespace {

// The old default camera (before the free-space search): from +Z, 3.5 m away, 0.6 m up.
constexpr CameraOrbit kOldDefaultOrbit{0.f, 3.5f, 0.6f};

// `n` unit directions spread evenly over the sphere (a Fibonacci spiral), fixed.
std::vector<glm::vec3> spreadDirections(int n) {
    std::vector<glm::vec3> dirs;
    const float golden = glm::pi<float>() * (3.f - std::sqrt(5.f));
    for (int i = 0; i < n; ++i) {
        const float y = 1.f - 2.f * (float(i) + 0.5f) / float(n);
        const float r = std::sqrt(std::max(0.f, 1.f - y * y));
        const float phi = golden * float(i);
        dirs.emplace_back(r * std::cos(phi), y, r * std::sin(phi));
    }
    return dirs;
}

// The candidates of DefaultViewpointRules, in order.
std::vector<CameraOrbit> candidateOrbits(float radius) {
    std::vector<CameraOrbit> out{kOldDefaultOrbit};
    std::vector<float> distances;
    for (const float f : {3.f, 2.f, 4.f, 1.5f, 6.f}) {
        const float d = std::max(0.8f, f * radius);
        if (std::find(distances.begin(), distances.end(), d) == distances.end())
            distances.push_back(d);
    }
    for (const float d : distances)
        for (const float h : {0.17f, 0.45f, 0.f, -0.25f})
            for (int k = 0; k < 12; ++k) {
                // 0, +30, -30, +60, -60, ... 180 degrees.
                const float step = float((k + 1) / 2) * (k % 2 ? 1.f : -1.f);
                out.push_back({glm::radians(30.f * step), d, h * d});
            }
    return out;
}

bool isBackFace(const Hit& hit, glm::vec3 dir) {
    const bool doubleSided =
        hit.primitive && hit.primitive->material && hit.primitive->material->doubleSided;
    return !doubleSided && glm::dot(hit.geometricNormal, dir) > 0.f;
}

// The share of `dirs` from `eye` that meet no surface (how open to the sky it stands), or
// nullopt when the eye is not in free space (DefaultViewpointRules).
std::optional<float> freeSpaceOpenness(const EmbreeScene& s, glm::vec3 eye,
                                       const std::vector<glm::vec3>& dirs) {
    using R = DefaultViewpointRules;
    int back = 0, open = 0;
    for (const glm::vec3& d : dirs) {
        const std::optional<Hit> hit = s.intersect(eye, d);
        if (!hit) {
            ++open;
            continue;
        }
        if (hit->t < R::kClearance) return std::nullopt;
        if (isBackFace(*hit, d) && ++back > R::kMaxBackFaceHits) return std::nullopt;
    }
    return float(open) / float(dirs.size());
}

std::string metres(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", double(v));
    return buf;
}

} // namespace

CameraOrbit defaultViewpointOrbit(const ProbeScene& scene) {
    using R = DefaultViewpointRules;
    if (scene.markup.mirrorEntities.empty()) return kOldDefaultOrbit; // nothing to see
    const glm::vec3 centre = markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    Aabb mirrors;
    for (ecs::Entity e : scene.markup.mirrorEntities)
        mirrors.extend(meshWorldBounds(scene.registry, e));
    const float radius = mirrors.empty() ? 0.f : 0.5f * glm::length(mirrors.max - mirrors.min);

    // EmbreeScene only reads the registry (its meshes and world transforms).
    const EmbreeScene full(const_cast<ecs::Registry&>(scene.registry));
    const auto& mirrorSet = scene.markup.mirrorEntities;
    const EmbreeScene::Filter environment = [&](ecs::Entity e) { return !mirrorSet.count(e); };
    const std::vector<glm::vec3> dirs = spreadDirections(R::kFreeSpaceRays);
    constexpr int kW = 48, kH = 36;
    const int minMirrorPixels = int(std::ceil(R::kMinMirrorShare * float(kW * kH)));

    // How open the reflectors' surroundings are: the share of rays from the centre that meet
    // no environment surface.
    int centreOpen = 0;
    for (const glm::vec3& d : dirs)
        centreOpen +=
            full.intersect(centre, d, 1e-4f, std::numeric_limits<float>::infinity(), &environment)
                ? 0
                : 1;
    const float centreOpenness = float(centreOpen) / float(dirs.size());

    // The eye of `o` in free space with the centre in sight: its openness, else nullopt.
    auto standsFree = [&](const CameraOrbit& o) -> std::optional<float> {
        const glm::vec3 eye = centre + glm::vec3(o.distance * std::sin(o.angle), o.height,
                                                 o.distance * std::cos(o.angle));
        const std::optional<float> openness = freeSpaceOpenness(full, eye, dirs);
        if (!openness) return std::nullopt;
        const glm::vec3 toCentre = centre - eye;
        const float dist = glm::length(toCentre);
        if (full.intersect(eye, toCentre / dist, 1e-4f, dist, &environment)) return std::nullopt;
        return openness;
    };
    struct Verdict {
        bool valid = false;   // free, the centre in sight, enough mirror pixels
        bool swingOk = false; // the walk's swing ends free with the centre in sight too
        bool asEnclosed = false;
    };
    auto judge = [&](const CameraOrbit& o) {
        Verdict v;
        const std::optional<float> openness = standsFree(o);
        if (!openness) return v;
        const CameraView view = orbitCameraView(centre, kW, kH, o.angle, o.distance, o.height);
        int mirrorPixels = 0;
        for (int y = 0; y < kH && mirrorPixels < minMirrorPixels; ++y)
            for (int x = 0; x < kW; ++x) {
                glm::vec3 origin, dir;
                view.primaryRay(x, y, origin, dir);
                const std::optional<Hit> hit = full.intersect(origin, dir);
                mirrorPixels += hit && mirrorSet.count(hit->entity) ? 1 : 0;
            }
        v.valid = mirrorPixels >= minMirrorPixels;
        v.asEnclosed = *openness <= centreOpenness + R::kMaxExtraOpenness;
        v.swingOk = true;
        for (const float swing :
             {-R::kWalkSwing, -0.5f * R::kWalkSwing, 0.5f * R::kWalkSwing, R::kWalkSwing})
            v.swingOk = v.swingOk && standsFree({o.angle + swing, o.distance, o.height});
        return v;
    };

    const std::vector<CameraOrbit> candidates = candidateOrbits(radius);
    std::vector<std::optional<Verdict>> verdicts(candidates.size());
    for (int pass = 0; pass < 3; ++pass)
        for (std::size_t i = 0; i < candidates.size(); ++i) {
            if (!verdicts[i]) verdicts[i] = judge(candidates[i]);
            const Verdict& v = *verdicts[i];
            if (v.valid && (pass == 2 || v.swingOk) && (pass >= 1 || v.asEnclosed))
                return candidates[i];
        }
    float nearest = candidates.front().distance, farthest = nearest;
    for (const CameraOrbit& o : candidates) {
        nearest = std::min(nearest, o.distance);
        farthest = std::max(farthest, o.distance);
    }
    throw Error(scene.path, "camera",
                "no free viewpoint around the reflectors sees them (centre " + metres(centre.x) +
                    "," + metres(centre.y) + "," + metres(centre.z) + "; " +
                    std::to_string(candidates.size()) + " viewpoints " + metres(nearest) + " to " +
                    metres(farthest) +
                    " m away: each stands inside geometry or behind a surface, or sees under " +
                    std::to_string(int(R::kMinMirrorShare * 100.f)) +
                    "% reflector pixels); give the scene a camera node in the glTF, or move the "
                    "reflector into free space or add one there with --add-reflector "
                    "sphere:x,y,z,r");
}

namespace {

// The scene's first camera node, or the null entity.
ecs::Entity sceneCameraEntity(const ProbeScene& scene) {
    for (ecs::Entity e : scene.loaded.entities)
        if (scene.registry.find<Camera>(e) && scene.registry.find<Transform>(e)) return e;
    return ecs::kNullEntity;
}

// A camera node's view: it looks down its local -Z, so the view matrix is its world's inverse.
CameraView cameraNodeView(const Camera& cam, const glm::mat4& world, int width, int height) {
    CameraView v;
    v.view = glm::inverse(world);
    v.proj = glm::perspective(cam.yfov, float(width) / float(height), cam.znear, cam.zfar);
    v.width = width;
    v.height = height;
    return v;
}

// The span of the camera's animation when it has one that moves.
std::optional<std::pair<float, float>> cameraSpan(const ProbeScene& scene, ecs::Entity camera) {
    if (camera.isNull()) return std::nullopt;
    const auto span = animatedRange(scene.registry, camera);
    if (!span || !(span->second > span->first)) return std::nullopt;
    return span;
}

} // namespace

CameraView sceneCameraView(const ProbeScene& scene, int width, int height) {
    if (const ecs::Entity e = sceneCameraEntity(scene); !e.isNull())
        return cameraNodeView(*scene.registry.find<Camera>(e),
                              scene.registry.find<Transform>(e)->world, width, height);
    const CameraOrbit o = scene.defaultView.get([&] { return defaultViewpointOrbit(scene); });
    return orbitCameraView(markupProbeCentre(scene.registry, scene.markup, scene.loaded), width,
                           height, o.angle, o.distance, o.height);
}

CameraOrbit sceneCameraOrbit(const ProbeScene& scene) {
    const glm::vec3 c = markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    const glm::vec3 e = sceneCameraView(scene, 64, 48).eye() - c;
    return {std::atan2(e.x, e.z), std::max(0.5f, std::hypot(e.x, e.z)), e.y};
}

CameraView walkOrbitCameraView(const ProbeScene& scene, int width, int height, float t) {
    const CameraOrbit o = sceneCameraOrbit(scene);
    return orbitCameraView(
        markupProbeCentre(scene.registry, scene.markup, scene.loaded), width, height,
        o.angle + DefaultViewpointRules::kWalkSwing * std::sin(glm::two_pi<float>() * t),
        o.distance, o.height);
}

bool sceneCameraMoves(const ProbeScene& scene) {
    return cameraSpan(scene, sceneCameraEntity(scene)).has_value();
}

CameraView cameraPathView(const ProbeScene& scene, int width, int height, float t) {
    const ecs::Entity camera = sceneCameraEntity(scene);
    if (camera.isNull())
        throw Error(scene.path, "path",
                    "the camera path follows the scene's camera node, and the scene has none");
    const auto span = cameraSpan(scene, camera);
    if (!span)
        throw Error(scene.path, "path",
                    "the camera path follows the animation of the scene's camera node, and "
                    "nothing animates it (its first animation has no channel moving it or a "
                    "parent over time)");
    const float seconds = span->first + std::clamp(t, 0.f, 1.f) * (span->second - span->first);
    return cameraNodeView(*scene.registry.find<Camera>(camera),
                          animatedWorld(scene.registry, camera, seconds), width, height);
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
    f.flavour = r.probeFlavour(m);
    if (m.contains("source")) f.source = r.string(m, "source", "");
    f.skySourceGiven = m.contains("sky_source");
    if (f.skySourceGiven) f.skySource = r.string(m, "sky_source", "");
    if (m.contains("sky"))
        f.skyFile =
            r.fileInFolder(m["sky"], "sky.", std::filesystem::path(manifestPath).parent_path());
    f.inputs = manifestProbeInputs(m, manifestPath);
    return f;
}

} // namespace specula
