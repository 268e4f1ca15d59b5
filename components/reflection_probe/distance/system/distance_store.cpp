#include "distance_store.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"

#include <algorithm>

namespace specula {

DistanceVariant DistanceVariant::filter() const {
    DistanceVariant v = *this;
    if (v.output != 0) v.features &= ~(kFeatureFresnel | kFeatureGlossy);
    if (!(v.features & kFeatureGlossy)) v.roughnessMap = false;
    return v;
}

std::string DistanceVariant::name() const {
    return distanceFeatureName(features) + (roughnessMap ? "+roughness-map" : "");
}

gpu::Program DistanceVariant::build() const {
    return buildReflectorProgram(
        "components/reflection_probe/distance/shaders/distance_reflector.frag",
        distanceDefines(features, roughnessMap), output);
}

DistanceProbeGpu DistanceStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats&) {
    return DistanceGpuProbe::load(assets_.get(
        manifest.path, [&] { return storedDistanceAsset(readDistanceProbe(manifest)); }));
}

void DistanceStore::applySettings(DistanceProbeGpu& g, const DistanceProbe& settings,
                                  ProbeFrameStats& stats) {
    if (g.applySettings(settings)) ++stats.textureUploads;
    ++stats.parameterUploads;
}

std::size_t DistanceStore::gpuBytesOf(const DistanceProbeGpu& g) const {
    return g.gpuBytes();
}

void DistanceStore::drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                  const Reflector& r, const DistanceProbeGpu& p,
                                  const DistanceProbe&) {
    DistanceVariant v{p.config.features, ctx.output, usesRoughnessMap(r)};
    if (r.fresnelF0 >= 0.f) v.features |= kFeatureFresnel;
    if (r.roughness > 0.f) v.features |= kFeatureGlossy; // NaN: a mirror
    const bool glossy = (v.filter().features & kFeatureGlossy) != 0;
    if (glossy) prepareGlossy(p, ctx.stats); // made in sync, unless it turned rough since
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.filter().name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    p.bindTo(prog.id(), DistanceBindings{}, glossy, &ggxAlbedo_);
    prog.setUniform("uF0", r.fresnelF0);
    if (glossy) {
        prog.setUniform("uRoughness", r.roughness);
        if (v.filter().roughnessMap) roughnessMaps_.bind(prog, r, ctx.stats);
    }
    ctx.scene.drawEntity(reflector, prog);
}

void DistanceStore::syncReflectors(ecs::Registry& registry, ProbeFrameStats& stats) {
    registry.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
        if (!(r.roughness > 0.f)) return;
        if (const DistanceProbeGpu* g = probe(r.probe)) prepareGlossy(*g, stats);
    });
    syncRoughnessMaps(registry, stats);
}

void DistanceStore::prepareGlossy(const DistanceProbeGpu& p, ProbeFrameStats& stats) {
    if (p.glossyChain) return;
    p.setGlossyChain(chainOf(p.asset)); // throws before any change
    // The albedo table every rough reflector reads, made with the first chain (one upload).
    if (!ggxAlbedo_) ggxAlbedo_ = gpu::createGgxAlbedoTexture();
    ++stats.textureUploads;
}

std::shared_ptr<const CubeChain>
DistanceStore::chainOf(const std::shared_ptr<const DistanceProbeAsset>& a) {
    std::erase_if(chains_, [](const auto& entry) { return entry.second.asset.expired(); });
    SharedChain& cached = chains_[a.get()];
    std::shared_ptr<const CubeChain> chain = cached.chain.lock();
    if (chain && cached.asset.lock() == a) return chain;
    chain = std::make_shared<const CubeChain>(glossyChainOf(*a));
    cached = {a, chain};
    return chain;
}

std::shared_ptr<const CubeChain> DistanceStore::glossyChain(ecs::Entity e) const {
    const DistanceProbeGpu* g = probe(e);
    return g ? g->glossyChain : nullptr;
}

const DistanceProbeAsset* DistanceStore::asset(ecs::Entity e) const {
    const DistanceProbeGpu* g = probe(e);
    return g ? g->asset.get() : nullptr;
}

const DistanceLookupConfig* DistanceStore::config(ecs::Entity e) const {
    const DistanceProbeGpu* g = probe(e);
    return g ? &g->config : nullptr;
}

} // namespace specula
