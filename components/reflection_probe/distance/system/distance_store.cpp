#include "distance_store.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"

#include <algorithm>

namespace specula {

namespace {

// Object layers stored as half floats (RGBA16F tiles, distance included) when they fit. The
// bench's layered rows (quick, 256^2 faces) moved from whole float layers to half tiles by
// +0.001 dB or less (room env 32.536 -> 32.537 dB, truck_room 28.867 -> 28.868 dB,
// fetches/px unchanged), and the tiles take half the memory.
constexpr bool kHalfObjectLayers = true;

} // namespace

DistanceProbeAsset storedDistanceAsset(DistanceProbeAsset asset) {
    if (kHalfObjectLayers && objectLayersFitHalf(asset)) roundObjectLayersToHalf(asset);
    return asset;
}

LayerTiles storedLayerTiles(const DistanceProbeAsset& stored) {
    return tileObjectLayers(stored, kLayerTileSize,
                            kHalfObjectLayers && objectLayersFitHalf(stored));
}

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
    auto bit = [&](std::uint32_t b) { return (features & b) ? "1" : "0"; };
    std::vector<std::string> defines;
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.define) defines.push_back(std::string(row.define) + "=" + bit(row.feature));
    defines.push_back(std::string("HAS_LAYERS=") + bit(kFeatureLayers));
    // The store keeps the object layers as tiles (uploadLayerTiles).
    defines.push_back(std::string("LAYER_TILES=") + bit(kFeatureLayers));
    defines.push_back(std::string("HAS_GLOSSY=") + bit(kFeatureGlossy));
    defines.push_back(std::string("HAS_ROUGHNESS_MAP=") + (roughnessMap ? "1" : "0"));
    defines.push_back(std::string("HAS_FRESNEL=") + bit(kFeatureFresnel));
    defines.push_back("OUTPUT=" + std::to_string(output));
    return gpu::buildProgram(
        gpu::ShaderSource::file("components/reflection_probe/shaders/reflector.vert"),
        gpu::ShaderSource::file(
            "components/reflection_probe/distance/shaders/distance_reflector.frag"),
        defines);
}

DistanceProbeGpu DistanceStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats&) {
    DistanceProbeGpu g;
    // The tiles' atlas holds half floats when they fit: the CPU copy (what the twin reads)
    // holds the same rounded values.
    g.asset = assets_.get(manifest.path,
                          [&] { return storedDistanceAsset(readDistanceProbe(manifest)); });
    if (!g.asset->sky.empty()) g.sky = uploadSkyTexture(g.asset->sky);
    return g;
}

void DistanceStore::applySettings(DistanceProbeGpu& g, const DistanceProbe& settings,
                                  ProbeFrameStats& stats) {
    const DistanceProbeAsset& a = *g.asset;
    DistanceLookupConfig config = makeLookupConfig(settings, a); // throws before any change
    // Only the layers the method reads go to the GPU: the composite alone unless layered. A
    // texture that already holds them is kept, so a method edit re-uploads only to grow.
    const int needed = (config.features & kFeatureLayers) ? int(a.layers.size()) : 1;
    if (needed > g.layersUploaded) {
        if (g.layersUploaded == 0) {
            g.layers = createCubeArray(a.faceRes, 1);
            uploadCube(g.layers, 0, a.layers.front());
        }
        if (needed > 1) {
            const LayerTiles tiles = storedLayerTiles(a);
            g.tiles = uploadLayerTiles(tiles);
            g.tileGrid = glm::ivec2(tiles.tileSize, tiles.tilesPerFace);
            g.tileBytes = layerTileBytes(tiles);
        }
        g.layersUploaded = needed;
        ++stats.textureUploads;
    }
    g.config = std::move(config);
    g.params.upload(g.config);
    ++stats.parameterUploads;
}

std::size_t DistanceStore::gpuBytesOf(const DistanceProbeGpu& g) const {
    const DistanceProbeAsset& a = *g.asset;
    return (g.layersUploaded > 0 ? cubeArrayBytes(a.faceRes, 1) : 0) + g.tileBytes +
           (a.sky.empty() ? 0 : skyTextureBytes(a.sky)) +
           (g.glossyChain ? chainArrayBytes(*g.glossyChain) : 0);
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
    glBindTextureUnit(1, p.layers.id());
    glBindTextureUnit(2, p.sky.id());
    prog.setUniform("uLayers", 1);
    prog.setUniform("uSky", 2);
    prog.setUniform("uHasSky", p.sky.id() != 0 ? 1 : 0);
    if (v.features & kFeatureLayers) {
        glBindTextureUnit(5, p.tiles.atlas.id());
        glBindTextureUnit(6, p.tiles.table.id());
        prog.setUniform("uTileAtlas", 5);
        prog.setUniform("uTileTable", 6);
        prog.setUniform("uTileGrid", p.tileGrid);
    }
    p.params.bind(glsl::kDistanceParamsBinding);
    prog.setUniform("uF0", r.fresnelF0);
    if (glossy) {
        glBindTextureUnit(3, p.glossyTexture.id());
        prog.setUniform("uChain", 3);
        prog.setUniform("uRoughness", r.roughness);
        prog.setUniform("uChainLevels", int(p.glossyChain->levels.size()));
        glBindTextureUnit(4, ggxAlbedo_.id());
        prog.setUniform("uGgxAlbedo", 4);
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
    std::shared_ptr<const CubeChain> chain = chainOf(p.asset); // throws before any change
    p.glossyTexture = uploadChainArray(*chain);
    p.glossyChain = std::move(chain);
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
