#pragma once
// The reference every probe flavour is measured against: Embree traces primary rays,
// perfect mirror reflections and the house shading of environment surfaces, the same
// shading the rasteriser and the probe bake use.
#include "engine/ecs/registry.h"
#include "engine/image/image.h"
#include "engine/math/camera.h"
#include "engine/raytrace/embree_scene.h"

#include <functional>
#include <limits>
#include <optional>
#include <unordered_set>

#include <glm/glm.hpp>

namespace specula {

struct TraceOptions {
    int maxBounces = 4; // mirror reflections followed; a ray still on a mirror after that is black
    // Reflected rays see the environment only (other mirrors invisible), which is exactly
    // what a probe can represent; primary rays still see every mirror.
    bool environmentOnly = false;
    std::unordered_set<ecs::Entity> mirrors;
    const Image* sky = nullptr; // equirectangular, linear; black when null. Not owned.
    // Multiplies what a mirror reflects (e.g. a tint or constant Fresnel). Called from many
    // threads at once. Empty: white.
    std::function<glm::vec3(ecs::Entity)> mirrorTint;
};

struct EnvSample {
    glm::vec3 radiance{0.f};
    float distance = std::numeric_limits<float>::infinity(); // Euclidean, +inf on a miss
    ecs::Entity entity = ecs::kNullEntity;
    bool hit = false;
};

struct GroundTruthImage {
    Image color;      // RGB, linear
    Image mirrorMask; // 1 channel: 1 where the primary ray hits a mirror, else 0
    Image depth;      // 1 channel: distance from the eye to the primary hit, +inf on a miss
};

class GroundTruthTracer {
public:
    // Builds the environment scene (every mesh not in options.mirrors) and the full scene
    // from Transform::world: run updateWorldTransforms first. The registry is not kept.
    GroundTruthTracer(ecs::Registry& registry, TraceOptions options);

    // Radiance arriving at `origin` from direction `dir`; `depth` counts the mirror
    // reflections already followed. Thread-safe.
    glm::vec3 radiance(glm::vec3 origin, glm::vec3 dir, int depth = 0) const;

    // The environment alone, for probe baking. `only`: when given, surfaces of entities it
    // rejects are transparent (one layer at a time). A miss returns the sky radiance with
    // hit = false and distance = +inf.
    EnvSample traceEnvironment(glm::vec3 origin, glm::vec3 dir,
                               const std::function<bool(ecs::Entity)>* only = nullptr) const;

    // The sky in direction `dir` (GPU-like: bilinear, u repeats, v clamps).
    glm::vec3 sky(glm::vec3 dir) const;

    // One primary ray per pixel centre, rows in parallel.
    GroundTruthImage render(const CameraView& camera) const;

    const TraceOptions& options() const { return options_; }
    const EmbreeScene& environmentScene() const { return environment_; }
    const EmbreeScene& fullScene() const { return full_; }

private:
    glm::vec3 shade(const Hit& hit) const;
    // Radiance along `dir` given what the ray hit (nullopt: the sky).
    glm::vec3 resolve(const std::optional<Hit>& hit, glm::vec3 dir, int depth) const;

    TraceOptions options_;
    EmbreeScene environment_;
    EmbreeScene full_;
};

} // namespace specula
