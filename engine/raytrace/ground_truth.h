#pragma once
// The reference every probe flavour is measured against: Embree traces primary rays,
// perfect mirror reflections, glossy (GGX) reflections and the house shading of environment
// surfaces, the same shading the rasteriser and the probe bake use.
//
// Glossy reflectors (TraceOptions::mirrorRoughness > 0). The truth is the reflected radiance
// of the full microfacet BRDF with Fresnel = 1,
//     L(v) = tint * integral over the hemisphere of f(v, l) L(l) (n.l) dl,
//     f = D(h) G2(v, l) F / (4 (n.l) (n.v)),  F = 1,
// with D the GGX (Trowbridge-Reitz) distribution of alpha = roughness^2 and G2 Smith's
// height-correlated masking-shadowing 1 / (1 + Lambda(v) + Lambda(l)). It is NOT the
// normalised, split-sum prefiltered lobe: energy lost to masking and to directions below the
// horizon is lost, so under a uniform white sky a rough reflector shows its directional
// albedo E(v) <= 1, not 1 (the furnace test checks this against quadrature).
// Estimator: the visible normals are sampled (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals"), l = reflect(-v, h); the weight f (n.l) / pdf(l) is then exactly
// G2(v, l) / G1(v) in [0, 1] (0 below the horizon), so no sample can blow up, even at
// grazing view. The estimate is the mean of weight x radiance(l) over glossySamples samples.
// The 2D samples are an Owen-scrambled Sobol (0, 2)-sequence, scrambled per pixel by a hash
// of (seed, pixel): every pixel is an independent randomisation (unbiased, seed-to-seed
// differences measure the noise) and nothing depends on thread scheduling. Being stratified,
// the noise falls faster than Monte Carlo's 1/sqrt(N): in the room, 16x the samples cut the
// seed-to-seed RMSE about 7-fold (+17 dB), not 4-fold (+12 dB). Beyond the first
// rough hit of a path, each sample follows ONE sampled ray per rough hit (a path tracer), with
// hashed random numbers of (seed, pixel, sample, bounce), up to maxBounces as for mirrors.
// Roughness 0 (or negative, or NaN) takes the perfect-mirror code path unchanged, bit for
// bit; roughness > 0 is clamped to [1e-3, 1] (alpha >= 1e-6).
// v is the view direction about the shading normal turned towards the viewer; where an
// interpolated normal faces away from the eye (n.v <= 1e-4), v is bent to n.v = 1e-4.
#include "engine/ecs/registry.h"
#include "engine/image/image.h"
#include "engine/image_io/compare.h"
#include "engine/math/camera.h"
#include "engine/raytrace/embree_scene.h"

#include <cstdint>
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
    // GGX roughness of a mirror at a hit (alpha = roughness^2; the hit's entity and its
    // TEXCOORD_0, for a roughness map), at most 1; <= 0 (and NaN) is a perfect mirror. Called
    // from many threads at once. Empty: every mirror has roughness 0.
    std::function<float(ecs::Entity, glm::vec2 uv)> mirrorRoughness;
    int glossySamples = 256; // samples at the first rough hit of a pixel's path (at least 1)
    std::uint32_t seed = 1;  // the glossy sample sequence; same seed, same image, bit for bit
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
    // reflections already followed. Thread-safe. Glossy samples are scrambled by (seed, the
    // bits of origin, dir and depth): deterministic, and independent for distinct rays.
    glm::vec3 radiance(glm::vec3 origin, glm::vec3 dir, int depth = 0) const;

    // The environment alone, for probe baking. `only`: when given, surfaces of entities it
    // rejects are transparent (one layer at a time). A miss returns the sky radiance with
    // hit = false and distance = +inf.
    EnvSample traceEnvironment(glm::vec3 origin, glm::vec3 dir,
                               const std::function<bool(ecs::Entity)>* only = nullptr) const;

    // The sky in direction `dir` (GPU-like: bilinear, u repeats, v clamps).
    glm::vec3 sky(glm::vec3 dir) const;

    // One primary ray per pixel centre, rows in parallel; a pixel on a rough mirror averages
    // glossySamples reflected samples scrambled by (options().seed, pixel). render(camera,
    // seed) renders with another seed (the noise floor); render(camera) uses options().seed.
    GroundTruthImage render(const CameraView& camera) const;
    GroundTruthImage render(const CameraView& camera, std::uint32_t seed) const;

    const TraceOptions& options() const { return options_; }
    const EmbreeScene& environmentScene() const { return environment_; }
    const EmbreeScene& fullScene() const { return full_; }

private:
    struct PathState; // where a glossy sample path stands (null before its first rough hit)

    glm::vec3 shade(const Hit& hit) const;
    glm::vec3 trace(glm::vec3 origin, glm::vec3 dir, int depth, std::uint64_t stream,
                    PathState* path) const;
    // Radiance along `dir` given what the ray hit (nullopt: the sky). `stream` keys the
    // glossy sample sequence (seed and pixel, or seed and ray).
    glm::vec3 resolve(const std::optional<Hit>& hit, glm::vec3 dir, int depth, std::uint64_t stream,
                      PathState* path) const;
    glm::vec3 glossy(const Hit& hit, glm::vec3 d, float roughness, int depth, std::uint64_t stream,
                     PathState* path) const;

    TraceOptions options_;
    EmbreeScene environment_;
    EmbreeScene full_;
};

// The noise floor of the glossy ground truth: the same view rendered with two seeds and
// compared (compareImages) on the mirror pixels (mirrorMask, the mask the accuracy reports
// use, so perfect-mirror pixels count as exact). Two independent estimates differ by twice
// the variance of one, so the truth's own error against the exact integral sits about 3 dB
// above this PSNR. A probe's PSNR against the truth cannot be trusted near this floor; raise
// glossySamples until it sits well above the probe's. Costs two renders.
struct GroundTruthNoise {
    ImageStats stats;  // seed A against seed B on the mirror pixels
    double psnr = 0.0; // stats.psnr (+inf without rough pixels; NaN without mirror pixels)
    int samples = 0;   // glossySamples used
    std::uint32_t seedA = 1, seedB = 2;
};
GroundTruthNoise measureNoiseFloor(const GroundTruthTracer& tracer, const CameraView& camera,
                                   std::uint32_t seedA = 1, std::uint32_t seedB = 2);

} // namespace specula
