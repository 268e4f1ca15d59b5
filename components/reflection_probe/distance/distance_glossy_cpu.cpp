#include "distance_glossy_cpu.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"

#include "engine/core/error.h"
#include "engine/core/glsl_host.h"

#include <algorithm>
#include <cmath>

namespace specula {
namespace glsl {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "components/reflection_probe/distance/shaders/distance_glossy.glsl.h"
#pragma GCC diagnostic pop
} // namespace
} // namespace glsl

float glossyLobeHalfAngle(float alpha) {
    return glsl::glossyLobeHalfAngle(alpha);
}

namespace {

DistanceProbe withMethod(DistanceProbe p, DistanceMethod m) {
    p.method = m;
    return p;
}

const DistanceProbe& rectifying(const DistanceProbe& search) {
    if (search.method != DistanceMethod::Bisection && search.method != DistanceMethod::Secant)
        throw Error("", "glossy search method", "expected bisection or secant");
    return search;
}

// The chain, once the search method is known to be good (before the prefilter's time).
std::shared_ptr<const CubeChain> chainFor(const DistanceProbeAsset& asset,
                                          const DistanceProbe& search,
                                          const GgxPrefilterOptions& prefilter) {
    rectifying(search);
    return std::make_shared<const CubeChain>(glossyChainOf(asset, prefilter));
}

} // namespace

const char* glossyModeName(GlossyMode mode) {
    switch (mode) {
    case GlossyMode::EnvmapChain:
        return "envmap-chain";
    case GlossyMode::BoxprojChain:
        return "boxproj-chain";
    case GlossyMode::RectifiedRoughnessLevel:
        return "rectified-roughness";
    case GlossyMode::RectifiedFootprint:
        return "rectified-footprint";
    }
    return "?";
}

CpuGlossyDistanceProbe::CpuGlossyDistanceProbe(const DistanceProbeAsset& asset,
                                               const DistanceProbe& search,
                                               const GgxPrefilterOptions& prefilter)
    : chain_(chainFor(asset, search, prefilter)),
      envmap_(asset, makeLookupConfig(withMethod(search, DistanceMethod::Envmap), asset), chain_),
      boxproj_(asset, makeLookupConfig(withMethod(search, DistanceMethod::BoxProj), asset), chain_),
      rectified_(asset, makeLookupConfig(rectifying(search), asset), chain_) {}

const CpuDistanceProbe& CpuGlossyDistanceProbe::mirror(GlossyMode mode) const {
    if (mode == GlossyMode::EnvmapChain) return envmap_;
    if (mode == GlossyMode::BoxprojChain) return boxproj_;
    return rectified_;
}

CpuGlossyDistanceProbe::Sample CpuGlossyDistanceProbe::sample(glm::vec3 x, glm::vec3 lhat,
                                                              float roughness,
                                                              GlossyMode mode) const {
    if (mode != GlossyMode::RectifiedRoughnessLevel) {
        // The shader's glossy path of the mode's method.
        const CpuDistanceProbe::GlossySample g = mirror(mode).glossySample(x, lhat, roughness);
        return {g.radiance, g.level, g.t, g.hit};
    }
    // The same search, the level from roughness alone: the lobe's centre is the rectified
    // hit, or the direction when the search found nothing.
    const CpuDistanceProbe::CompositeHit h = rectified_.compositeHit(x, lhat);
    Sample s{h.radiance, 0.f, h.t, h.hit};
    if (!(roughness > 0.f)) return s; // a mirror: level 0 is the input, read as the mirror does
    const int levels = int(chain_->levels.size());
    s.level =
        glsl::glossyRoughnessLevel(std::min(roughness, 1.f), levels, chain_->levels[0][0].width);
    // Below level 1, the mirror's answer blended with level 1, as the shader reads.
    const glm::vec3 at = h.hit ? h.at : lhat;
    const float share = glsl::glossyMirrorShare(s.level);
    s.radiance = share > 0.f ? glm::mix(sampleChain(*chain_, at, 1.f), h.radiance, share)
                             : sampleChain(*chain_, at, s.level);
    return s;
}

} // namespace specula
