#include "distance_level_store.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/level_index.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"
#include "engine/log/log.h"
#include "engine/scene/mesh_bounds.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

namespace specula {
DistanceLevelVariant DistanceLevelVariant::filter() const {
    DistanceLevelVariant v = *this;
    if (v.output != 0) v.features &= ~kFeatureFresnel;
    // OUTPUT 1, 2 and 4 (TEXCOORD_0) write no colour; 3 (|n.v|) is the glossy twin's input.
    if (v.output == 1 || v.output == 2 || v.output == 4) v.features &= ~kFeatureGlossy;
    if (!(v.features & kFeatureGlossy)) v.roughnessMap = false;
    return v;
}

std::string DistanceLevelVariant::name() const {
    return "level " + distanceFeatureName(features) + (roughnessMap ? "+roughness-map" : "") +
           " k" + std::to_string(k) + " " + toString(LevelBlend(blend));
}

gpu::Program DistanceLevelVariant::build() const {
    return buildReflectorProgram(
        "components/reflection_probe/distance/shaders/distance_level_reflector.frag",
        distanceLevelDefines(features, k, LevelBlend(blend), roughnessMap), output);
}

DistanceLevelGpu DistanceLevelStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats&) {
    return DistanceLevelGpu::load(manifest.path, levelIndexFromJson(manifest.json, manifest.path),
                                  [&](const std::string& path) {
                                      return assets_.get(path,
                                                         [&] { return readDistanceProbe(path); });
                                  });
}

void DistanceLevelStore::applySettings(DistanceLevelGpu& g, const DistanceLevel& settings,
                                       ProbeFrameStats& stats) {
    g.applySettings(settings);
    ++stats.parameterUploads;
}

std::size_t DistanceLevelStore::gpuBytesOf(const DistanceLevelGpu& g) const {
    return g.gpuBytes();
}

void DistanceLevelStore::syncReflectors(ecs::Registry& registry, ProbeFrameStats& stats) {
    registry.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
        if (!(r.roughness > 0.f)) return;
        if (const DistanceLevelGpu* g = probe(r.probe)) prepareGlossy(*g, stats);
    });
    syncRoughnessMaps(registry, stats);
}

void DistanceLevelStore::prepareGlossy(const DistanceLevelGpu& g, ProbeFrameStats& stats) {
    if (!g.chains.empty()) return;
    g.setChains(g.makeChains()); // every chain made and checked before any is kept
    // The albedo table every rough reflector reads, made with the first chains (one upload).
    if (!ggxAlbedo_) ggxAlbedo_ = gpu::createGgxAlbedoTexture();
    ++stats.textureUploads;
}

const std::vector<std::shared_ptr<const CubeChain>>*
DistanceLevelStore::glossyChains(ecs::Entity e) const {
    const DistanceLevelGpu* g = probe(e);
    return g ? &g->chains : nullptr;
}

void DistanceLevelStore::drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                       const Reflector& r, const DistanceLevelGpu& g,
                                       const DistanceLevel& settings) {
    // The probes whose influence meets the reflector, in blend order: each pixel walks only
    // those. A reflector with no bounds gets every probe.
    const std::vector<GLint> candidates =
        g.candidatesFor(meshWorldBoundsConservative(ctx.registry, reflector));
    if (candidates.empty() && warnedOutside_.insert(reflector).second)
        log().warn("a reflector lies outside every influence volume of the level {}: the "
                   "probe nearest to each pixel answers there",
                   g.indexPath);

    DistanceLevelVariant v{g.methodFeature, settings.k, int(settings.blend), ctx.output,
                           usesRoughnessMap(r)};
    if (r.fresnelF0 >= 0.f) v.features |= kFeatureFresnel;
    if (r.roughness > 0.f) v.features |= kFeatureGlossy; // NaN: a mirror
    const bool glossy = (v.filter().features & kFeatureGlossy) != 0;
    if (glossy) prepareGlossy(g, ctx.stats); // made in sync, unless it turned rough since
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.filter().name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    g.bindTo(prog.id(), DistanceLevelBindings{}, candidates, glossy, &ggxAlbedo_);
    prog.setUniform("uF0", r.fresnelF0);
    if (glossy) {
        prog.setUniform("uRoughness", r.roughness);
        if (v.filter().roughnessMap) roughnessMaps_.bind(prog, r, ctx.stats);
    }
    ctx.scene.drawEntity(reflector, prog);
}

} // namespace specula
