#pragma once
// What the distance-cubemap lookup needs, derived once from the component and the cooked
// asset (not per frame). The GPU system uploads its block as is; the CPU twin reads it.
#include "components/reflection_probe/distance_probe_asset.h"
#include "components/reflection_probe/reflection_probe.h"
#include "engine/core/glsl_host.h"

#include <cstddef>
#include <cstdint>

namespace specula {

namespace glsl {
#include "components/reflection_probe/shaders/distance_params.glsl.h"
} // namespace glsl

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

// The shared parameter block (shaders/distance_params.glsl.h) plus the permutation bits,
// which pick the shader and so are not a uniform.
struct DistanceLookupConfig : glsl::DistanceParamsBlock {
    std::uint32_t features = 0; // DistanceFeature bits (Fresnel is added per reflector)
};

// N = ceil(log2(2D / d_e)), at least 1, at most 40 (d_e -> 0 must not loop forever).
int bisectionSteps(float range, float tolerance);

// Throws Error naming the probe when the method needs data the asset lacks.
DistanceLookupConfig makeLookupConfig(const ReflectionProbe& probe, const DistanceProbeAsset& a);

int methodIndex(LookupMethod m); // kMethod* value; Layered maps to -1

} // namespace specula
