#pragma once
// The CPU twin of a PEM probe's reflector pass, and the parameter block both run on: the
// store uploads pemParams(asset, settings) as is, and PemProbeCpu reads the same block, so
// the samples and weight the twin blends are the ones the shader blends (pemBlend).
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_blend.h"
#include "components/reflection_probe/pem/pem_probe.h"
#include "engine/core/glsl_host.h"

#include <cstddef>

namespace specula {

namespace glsl {
#include "components/reflection_probe/pem/shaders/pem_params.glsl.h"
} // namespace glsl

// The asset's sample parameters, in order (pemBlend's first argument).
std::vector<float> pemSampleParameters(const PemAsset& asset);

// The block the shader reads for `settings` on `asset`: box, face resolution, centre, the
// two samples' first array layers and weight from pemBlend, the distance geometry's search
// parameters (zero for box maps), the local layer's sphere (zero without one) and the maps'
// MIP levels.
glsl::PemParams pemParams(const PemAsset& asset, const PemProbe& settings);

class PemProbeCpu {
public:
    // Both must outlive the twin.
    PemProbeCpu(const PemAsset& asset, const glsl::PemParams& params)
        : asset_(&asset), params_(&params) {}

    // x: probe-local reflector point, l: unit reflected direction (the shader's OUTPUT 1/2).
    // Fresnel is not applied (the shader applies it after the lookup). onHull: the pixel's
    // triangle is on its reflector's hull (pem_hull.h; the shader's OUTPUT 3), so an asset's
    // local layer is skipped there as the shader skips it; assets without one ignore it.
    // f: the pixel's footprint, which picks the MIP level of multi-level maps.
    glm::vec3 radiance(glm::vec3 x, glm::vec3 l, bool onHull = true,
                       const PemFootprint& f = {}) const;

private:
    const PemAsset* asset_;
    const glsl::PemParams* params_;
};

} // namespace specula
