#include "distance_glossy_cpu.h"

#include "engine/core/error.h"
#include "engine/core/glsl_host.h"

#include <algorithm>
#include <cmath>

namespace specula {
namespace glsl {
namespace {
#include "components/reflection_probe/distance/shaders/distance_glossy.glsl.h"
} // namespace
} // namespace glsl

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

GgxPrefilterOptions withDInf(GgxPrefilterOptions o, float dInf) {
    o.dInf = dInf;
    return o;
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
    : envmap_(asset, makeLookupConfig(withMethod(search, DistanceMethod::Envmap), asset)),
      boxproj_(asset, makeLookupConfig(withMethod(search, DistanceMethod::BoxProj), asset)),
      rectified_(asset, makeLookupConfig(rectifying(search), asset)),
      chain_(prefilterGgx(asset.layers.at(0).faces, withDInf(prefilter, asset.dInf))) {}

const CpuDistanceProbe& CpuGlossyDistanceProbe::mirror(GlossyMode mode) const {
    if (mode == GlossyMode::EnvmapChain) return envmap_;
    if (mode == GlossyMode::BoxprojChain) return boxproj_;
    return rectified_;
}

CpuGlossyDistanceProbe::Sample CpuGlossyDistanceProbe::sample(glm::vec3 x, glm::vec3 lhat,
                                                              float roughness,
                                                              GlossyMode mode) const {
    // The lobe's centre: the mirror lookup's own search (box exit, rectified hit, or none).
    const CpuDistanceProbe::CompositeHit h = mirror(mode).compositeHit(x, lhat);
    Sample s{h.radiance, 0.f, h.t, h.hit};
    if (!(roughness > 0.f)) return s; // a mirror: level 0 is the input, read as the mirror does
    const int levels = int(chain_.levels.size());
    const float r = std::min(roughness, 1.f);
    // Envmap and a search that found nothing read by direction alone: the composite holds
    // the sky where it sees nothing, so its chain has the sky's blur there.
    const bool direction = mode == GlossyMode::EnvmapChain || !h.hit;
    s.level = mode == GlossyMode::RectifiedFootprint && !direction
                  ? glsl::glossyFootprintLevel(r, x, lhat, h.t, levels)
                  : glsl::glossyRoughnessLevel(r, levels);
    s.radiance = sampleChain(chain_, direction ? lhat : x + h.t * lhat, s.level);
    return s;
}

} // namespace specula
