#pragma once
// What the distance-cubemap lookup needs, derived once from the component and the cooked
// asset (not per frame). The GPU system uploads its block as is; the CPU twin reads it.
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/core/glsl_host.h"

#include <cstddef>
#include <cstdint>

namespace specula {

namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_params.glsl.h"
} // namespace glsl

// The shared parameter block (shaders/distance_params.glsl.h) plus the permutation bits,
// which pick the shader and so are not a uniform.
struct DistanceLookupConfig : glsl::DistanceParamsBlock {
    // Permutation bits: the methods' (kDistanceMethods) and kFeatureLayers; Fresnel and
    // glossy are added per reflector.
    std::uint32_t features = 0;
};

// N = ceil(log2(2D / d_e)), at least 1, at most 40 (d_e -> 0 must not loop forever).
int bisectionSteps(float range, float tolerance);

// Throws Error naming the asset's manifest when the method needs data the asset lacks.
DistanceLookupConfig makeLookupConfig(const DistanceProbe& settings, const DistanceProbeAsset& a);

// "layers+bisection+avgdist+glossy+fresnel": a feature mask's name, from the method table.
std::string distanceFeatureName(std::uint32_t features);

} // namespace specula
