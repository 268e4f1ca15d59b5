#pragma once
// What the distance-cubemap lookup needs, derived once from the component and the cooked
// asset (not per frame). The GPU system turns it into uniforms; the CPU twin reads it as is.
#include "components/reflection_probe/distance_probe_asset.h"
#include "components/reflection_probe/reflection_probe.h"

#include <cstdint>
#include <vector>

namespace specula {

// Bits of the shader permutation: one per compiled-in feature. The cache key is the mask.
enum DistanceFeature : std::uint32_t {
    kFeatureEnvmap = 1u << 0,
    kFeatureBoxProj = 1u << 1,
    kFeatureBisection = 1u << 2,
    kFeatureSecant = 1u << 3,
    kFeatureAvgDist = 1u << 4,
    kFeatureLayers = 1u << 5,
    kFeatureFresnel = 1u << 6,
};

struct DistanceLookupConfig {
    glm::vec3 boxMin{0.f}, boxMax{0.f};
    float range = 1.f;
    float tolerance = 0.01f;
    float dInf = 1e4f;
    int maxSteps = 1;
    int method = 0;                // kMethod* of distance_lookup.glsl.h (single-layer mode)
    int layerCount = 0;            // object layers used in layered mode
    std::vector<int> layerMethods; // index = layer (0 unused)
    std::vector<float> layerAvgDistance;
    std::vector<glm::vec3> layerBoxMin, layerBoxMax; // probe-local
    // Closest that layers i.. (every later one too) come to the probe centre: once a hit is
    // nearer than that, no later layer can occlude it and the layered loop ends.
    std::vector<float> layerReach;
    std::uint32_t features = 0; // DistanceFeature bits (Fresnel is added per reflector)
};

// N = ceil(log2(2D / d_e)), at least 1, at most 40 (d_e -> 0 must not loop forever).
int bisectionSteps(float range, float tolerance);

// Throws Error naming the probe when the method needs data the asset lacks.
DistanceLookupConfig makeLookupConfig(const ReflectionProbe& probe, const DistanceProbeAsset& a);

int methodIndex(LookupMethod m); // kMethod* value; Layered maps to -1

} // namespace specula
