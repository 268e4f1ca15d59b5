#include "distance_probe_cpu.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"
#include "engine/math/cube_face.h"
#include "engine/math/shading.h"

namespace specula {
namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"

// The fetches a twin reads through: what the GPU reads (bilinear radiance, nearest
// distance, clamped to the face edge).
struct TwinFetches {
    const DistanceProbeAsset* asset;
    const DistanceLookupConfig* config;

    const Image& face(int layer, vec3 dir, vec2& uv) const {
        const vec3 f = cubeFaceUv(dir);
        uv = vec2(f.x, f.y);
        return asset->layers[std::size_t(layer)].faces[std::size_t(f.z)];
    }
    float fetchDistance(int layer, vec3 dir) const {
        vec2 uv;
        const Image& img = face(layer, dir, uv);
        return sampleNearest(img, uv, Wrap::Clamp).a;
    }
    // The 2 x 2 texels a bilinear fetch at dir weighs, clamped at the face edge (what
    // textureGather returns; the order does not matter to its users).
    vec4 fetchDistanceGather(int layer, vec3 dir) const {
        vec2 uv;
        const Image& img = face(layer, dir, uv);
        const int x0 =
            std::clamp(int(std::floor(uv.x * float(img.width) - 0.5f)), 0, img.width - 1);
        const int y0 =
            std::clamp(int(std::floor(uv.y * float(img.height) - 0.5f)), 0, img.height - 1);
        const int x1 = std::min(x0 + 1, img.width - 1), y1 = std::min(y0 + 1, img.height - 1);
        return vec4(img.at(x0, y0)[3], img.at(x1, y0)[3], img.at(x0, y1)[3], img.at(x1, y1)[3]);
    }
    vec3 fetchRadiance(int layer, vec3 dir) const {
        vec2 uv;
        const Image& img = face(layer, dir, uv);
        if (sameSurface) return sameSurfaceBilinear(img, uv);
        return vec3(sampleBilinear(img, uv, Wrap::Clamp));
    }
    // Experiment::sameSurfaceRadiance: the bilinear weights of the texels whose distance
    // agrees with the nearest texel's (the one fetchDistance reads), renormalised.
    bool sameSurface = false;
    vec3 sameSurfaceBilinear(const Image& img, vec2 uv) const {
        const float d0 = sampleNearest(img, uv, Wrap::Clamp).a;
        const float dInf = config->params.dInf;
        const float slack = CpuDistanceProbe::sameSurfaceSlack(img.width);
        const float fx = uv.x * float(img.width) - 0.5f, fy = uv.y * float(img.height) - 0.5f;
        const float x0f = std::floor(fx), y0f = std::floor(fy);
        const float ax = fx - x0f, ay = fy - y0f;
        vec3 sum(0.f);
        float weight = 0.f;
        for (int j = 0; j < 4; ++j) {
            const int tx = wrapIndex(int(x0f) + (j & 1), img.width, Wrap::Clamp);
            const int ty = wrapIndex(int(y0f) + (j >> 1), img.height, Wrap::Clamp);
            const glm::vec4 t = img.rgba(tx, ty);
            const bool same =
                seesNothing(d0, dInf) ? seesNothing(t.a, dInf) : std::abs(t.a - d0) <= slack * d0;
            if (!same) continue;
            const float w = ((j & 1) ? ax : 1.f - ax) * ((j >> 1) ? ay : 1.f - ay);
            sum += w * vec3(t);
            weight += w;
        }
        // The nearest texel is one of the four, so some weight is left unless it sits exactly
        // on a zero weight; then the nearest texel alone answers.
        return weight > 0.f ? sum / weight : vec3(sampleNearest(img, uv, Wrap::Clamp));
    }
    static bool seesNothing(float d, float dInf) { return d >= 0.5f * dInf; }
    // Experiment::exactSearch: lookupLayer runs lookupExact instead of the layer's method.
    bool exactSearch = false;
    bool exactSearchOn() const { return exactSearch; }
    mutable bool skyFetched = false;
    vec3 fetchSky(vec3 dir) const {
        skyFetched = true;
        if (asset->sky.empty()) return vec3(0.f);
        return vec3(sampleBilinear(asset->sky, equirectUv(dir), Wrap::Repeat, Wrap::Clamp));
    }
    // The composite's glossy chain, as shaders/distance_glossy_gpu.glsl reads it.
    const CubeChain* chain = nullptr;
    vec3 fetchChainTexel(int level, int face, ivec2 texel) const {
        return vec3(chain->levels[std::size_t(level)][std::size_t(face)].rgba(texel.x, texel.y));
    }
    int chainFaceRes(int level) const { return chain->levels[std::size_t(level)][0].width; }

    const DistanceLayerParams& layerParams(int i) const { return config->layers[i]; }
    int layerMethod(int i) const { return layerParams(i).method; }
    float layerAvgDistance(int i) const { return layerParams(i).avgDistance; }
    vec3 layerBoxMin(int i) const { return layerParams(i).boxMin; }
    vec3 layerBoxMax(int i) const { return layerParams(i).boxMax; }
    float layerReach(int i) const { return layerParams(i).reach; }
};

// The shared lookup is included inside a struct so that its calls to fetchDistance and
// friends bind to the members above. The GPU compiles one permutation per probe; the CPU
// compiles every method in, once without layers and once with.
#define HAS_ENVMAP 1
#define HAS_BOXPROJ 1
#define HAS_BISECTION 1
#define HAS_SECANT 1
#define HAS_AVGDIST 1
#define HAS_MARCH 1
// The error budget's exact search (lookupExact), through the shader's own layer loop.
#define SPECULA_EXACT_SEARCH_HOOK

#define HAS_LAYERS 0
struct TwinSingle : TwinFetches {
#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_seen.glsl.h"
// The glossy path (HAS_GLOSSY): the seam-free chain sampler,
#include "engine/math/cube_chain_sample.glsl.h"
// then the lookup that reads the chain at the hit, and with its verdict (levels).
#include "components/reflection_probe/distance/shaders/distance_glossy_lookup.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_glossy_seen.glsl.h"
};
#undef HAS_LAYERS
#undef SPECULA_DISTANCE_LOOKUP_GLSL_H
#undef SPECULA_CUBE_CHAIN_SAMPLE_GLSL_H
#undef SPECULA_DISTANCE_GLOSSY_GLSL_H
#undef SPECULA_DISTANCE_GLOSSY_LOOKUP_GLSL_H

#define HAS_LAYERS 1
struct TwinLayered : TwinFetches {
#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
// The glossy path (HAS_GLOSSY): the seam-free chain sampler,
#include "engine/math/cube_chain_sample.glsl.h"
// then the lookup that reads the chain at the hit.
#include "components/reflection_probe/distance/shaders/distance_glossy_lookup.glsl.h"
};
#undef HAS_LAYERS

} // namespace glsl

struct CpuDistanceProbe::Twin {
    glsl::TwinSingle single;
    glsl::TwinLayered layered;
};

CpuDistanceProbe::CpuDistanceProbe(const DistanceProbeAsset& asset, DistanceLookupConfig config,
                                   std::shared_ptr<const CubeChain> glossy)
    : twin_(std::make_unique<Twin>()), config_(std::move(config)), glossy_(std::move(glossy)) {
    twin_->single.asset = twin_->layered.asset = &asset;
    twin_->single.config = twin_->layered.config = &config_;
    twin_->single.chain = twin_->layered.chain = glossy_.get();
}

CpuDistanceProbe::~CpuDistanceProbe() = default;

glm::vec3 CpuDistanceProbe::radiance(glm::vec3 x, glm::vec3 lhat, int& fetches,
                                     bool* sawSky) const {
    glsl::TwinFetches& f = (config_.features & kFeatureLayers)
                               ? static_cast<glsl::TwinFetches&>(twin_->layered)
                               : static_cast<glsl::TwinFetches&>(twin_->single);
    f.skyFetched = false;
    const glm::vec3 c = (config_.features & kFeatureLayers)
                            ? twin_->layered.probeRadiance(x, lhat, config_.params, fetches)
                            : twin_->single.probeRadiance(x, lhat, config_.params, fetches);
    if (sawSky) *sawSky = f.skyFetched;
    return c;
}

void CpuDistanceProbe::setExperiment(const Experiment& e) {
    experiment_ = e;
    twin_->single.sameSurface = twin_->layered.sameSurface = e.sameSurfaceRadiance;
    twin_->single.exactSearch = twin_->layered.exactSearch = e.exactSearch;
}

CpuDistanceProbe::CentreView CpuDistanceProbe::centreView(glm::vec3 h) const {
    glsl::TwinLayered& tw = twin_->layered;
    const glsl::DistanceParams& p = config_.params;
    const bool layered = (config_.features & kFeatureLayers) != 0;
    const int first = layered ? 1 : 0, last = layered ? p.layerCount : 0;
    const float r = glm::length(h);
    const float slack = r * (kSeenSlack + 4.f / float(std::max(p.faceRes, 1)));
    CentreView v;
    float bestAgreement = slack, nearest = p.dInf;
    int nearestLayer = -1;
    for (int i = first; i <= last; ++i) {
        const glm::vec4 d = tw.fetchDistanceGather(i, h);
        for (int j = 0; j < 4; ++j) {
            if (tw.isInfiniteDistance(d[j], p.dInf)) continue;
            if (std::abs(d[j] - r) <= bestAgreement) {
                bestAgreement = std::abs(d[j] - r);
                v.seen = true;
                v.layer = i;
            }
        }
        const float dn = tw.fetchDistance(i, h);
        if (!tw.isInfiniteDistance(dn, p.dInf) && dn < nearest) nearest = dn, nearestLayer = i;
    }
    if (!v.seen) {
        // What the centre sees in front instead (the composite shows the sky where nothing
        // is; the object layers leave it to the sky).
        if (nearestLayer < 0 && layered) {
            v.radiance = tw.fetchSky(glm::normalize(h));
            return v;
        }
        v.layer = nearestLayer < 0 ? 0 : nearestLayer;
    }
    v.radiance = tw.fetchRadiance(v.layer, h);
    return v;
}

glm::vec3 CpuDistanceProbe::sky(glm::vec3 dir) const {
    return twin_->single.fetchSky(dir);
}

CpuDistanceProbe::CompositeHit CpuDistanceProbe::compositeHit(glm::vec3 x, glm::vec3 lhat) const {
    const glsl::DistanceParams& p = config_.params;
    const glsl::LayerHit h = twin_->single.lookupLayer(
        p.method, 0, x, lhat, p, twin_->single.makeSpan(0.f, 2.f * p.range, p.maxSteps));
    if (!h.hit) return {twin_->single.fetchSky(lhat), p.dInf, false, h.fetches + 1, lhat};
    return {h.radiance, h.t, true, h.fetches, h.at};
}

CpuDistanceProbe::CompositeHit CpuDistanceProbe::lookupHit(glm::vec3 x, glm::vec3 lhat) const {
    const glsl::DistanceParams& p = config_.params;
    const glsl::LayerHit h = (config_.features & kFeatureLayers)
                                 ? twin_->layered.probeHit(x, lhat, p)
                                 : twin_->single.probeHit(x, lhat, p);
    if (!h.hit) return {twin_->single.fetchSky(lhat), p.dInf, false, h.fetches + 1, lhat};
    return {h.radiance, h.t, true, h.fetches, h.at};
}

CpuDistanceProbe::CompositeHit CpuDistanceProbe::objectLayerHit(int layer, glm::vec3 x,
                                                                glm::vec3 lhat) const {
    const glsl::DistanceParams& p = config_.params;
    if (!(config_.features & kFeatureLayers) || layer < 1 || layer > p.layerCount)
        throw Error(twin_->single.asset->manifestPath, "layers",
                    "object layer " + std::to_string(layer) + " is not in the layered lookup");
    const glsl::LayerHit h = twin_->layered.lookupObjectLayer(layer, x, lhat, p, p.dInf);
    return {h.radiance, h.t, h.hit, h.fetches, h.at};
}

CpuDistanceProbe::GlossySample CpuDistanceProbe::glossySample(glm::vec3 x, glm::vec3 lhat,
                                                              float roughness) const {
    if (!glossy_)
        throw Error(twin_->single.asset->manifestPath, "glossy chain",
                    "a glossy lookup needs the composite's prefiltered chain (glossyChainOf)");
    const int levels = int(glossy_->levels.size());
    const glsl::GlossySample s =
        (config_.features & kFeatureLayers)
            ? twin_->layered.probeGlossySample(x, lhat, roughness, config_.params, levels)
            : twin_->single.probeGlossySample(x, lhat, roughness, config_.params, levels);
    return {s.radiance, s.level, s.t, s.hit, s.fetches};
}

CpuDistanceProbe::Seen CpuDistanceProbe::seenRadiance(glm::vec3 x, glm::vec3 lhat) const {
    const auto s = twin_->single.probeSampleSeen(x, lhat, config_.params);
    return {s.radiance, s.visibility, s.seen, s.fetches, s.t};
}

CpuDistanceProbe::Seen CpuDistanceProbe::glossySeen(glm::vec3 x, glm::vec3 lhat,
                                                    float roughness) const {
    if (!glossy_)
        throw Error(twin_->single.asset->manifestPath, "glossy chain",
                    "a glossy lookup needs the composite's prefiltered chain (glossyChainOf)");
    const auto s = twin_->single.probeGlossySeen(x, lhat, roughness, config_.params,
                                                 int(glossy_->levels.size()));
    return {s.radiance, s.visibility, s.seen, s.fetches, s.t};
}

} // namespace specula
