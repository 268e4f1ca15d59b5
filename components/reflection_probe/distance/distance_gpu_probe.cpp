#include "distance_gpu_probe.h"

#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/shaders/distance_params.glsl.h"
#include "components/reflection_probe/host_probe.h"

namespace specula {

namespace {
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

std::vector<std::string> distanceFeatureDefines(std::uint32_t features, bool roughnessMap) {
    auto bit = [&](std::uint32_t b) { return (features & b) ? "1" : "0"; };
    std::vector<std::string> defines;
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.define) defines.push_back(std::string(row.define) + "=" + bit(row.feature));
    defines.push_back(std::string("HAS_GLOSSY=") + bit(kFeatureGlossy));
    defines.push_back(std::string("HAS_ROUGHNESS_MAP=") + (roughnessMap ? "1" : "0"));
    defines.push_back(std::string("HAS_FRESNEL=") + bit(kFeatureFresnel));
    return defines;
}

std::vector<std::string> distanceDefines(std::uint32_t features, bool roughnessMap) {
    std::vector<std::string> defines = distanceFeatureDefines(features, roughnessMap);
    const char* layers = (features & kFeatureLayers) ? "1" : "0";
    defines.push_back(std::string("HAS_LAYERS=") + layers);
    // The GPU probe keeps the object layers as tiles (uploadLayerTiles).
    defines.push_back(std::string("LAYER_TILES=") + layers);
    defines.push_back(std::string("COMPRESSED_COMPOSITE=") +
                      ((features & kFeatureCompressedComposite) ? "1" : "0"));
    return defines;
}

DistanceGpuProbe DistanceGpuProbe::load(std::shared_ptr<const DistanceProbeAsset> stored,
                                        gpu::TextureAllocator allocate) {
    DistanceGpuProbe g;
    g.asset = std::move(stored);
    g.allocate = std::move(allocate);
    if (!g.asset->sky.empty()) g.sky = uploadSkyTexture(g.asset->sky, g.allocate);
    return g;
}

std::vector<gpu::TextureSpec> DistanceGpuProbe::textureSpecs(const DistanceProbeAsset& a,
                                                             const DistanceLookupConfig& config,
                                                             const CubeChain* chain) {
    // In load, applySettings and setGlossyChain's order.
    std::vector<gpu::TextureSpec> specs;
    if (!a.sky.empty()) specs.push_back(skyTextureSpec(a.sky));
    if (a.compression == DistanceCompression::Bc6h) {
        specs.push_back(compressedCubeArraySpec(a.faceRes, 1));
        specs.push_back(distanceArraySpec(a.faceRes, 1, a.halfCompositeDistance));
    } else {
        specs.push_back(cubeArraySpec(a.faceRes, 1));
    }
    if ((config.features & kFeatureLayers) && a.layers.size() > 1)
        for (gpu::TextureSpec& t : layerTileSpecs(storedLayerTiles(a)))
            specs.push_back(std::move(t));
    if (chain && chain->levels.size() >= 2)
        specs.push_back(chainArraySpec(*chain, 1, chainHasBlocks(a, *chain)));
    return specs;
}

bool DistanceGpuProbe::applySettings(const DistanceProbe& settings) {
    const DistanceProbeAsset& a = *asset;
    DistanceLookupConfig made = makeLookupConfig(settings, a); // throws before any change
    // Only the layers the method reads go to the GPU. A texture that already holds them is
    // kept, so a method edit re-uploads only to grow.
    const int needed = (made.features & kFeatureLayers) ? int(a.layers.size()) : 1;
    const bool upload = needed > layersUploaded;
    if (upload) {
        if (layersUploaded == 0 && a.compression == DistanceCompression::Bc6h) {
            layers = createCompressedCubeArray(a.faceRes, 1, allocate);
            uploadCompressedCube(layers, 0, a.compositeBlocks);
            layerDistance = createDistanceArray(a.faceRes, 1, a.halfCompositeDistance, allocate);
            uploadDistance(layerDistance, 0, a.layers.front(), a.halfCompositeDistance);
        } else if (layersUploaded == 0) {
            layers = createCubeArray(a.faceRes, 1, allocate);
            uploadCube(layers, 0, a.layers.front());
        }
        if (needed > 1) {
            const LayerTiles t = storedLayerTiles(a);
            tiles = uploadLayerTiles(t, allocate);
            tileGrid = glm::ivec2(t.tileSize, t.tilesPerFace);
            tileBytes = layerTileBytes(t);
        }
        layersUploaded = needed;
    }
    config = std::move(made);
    params.upload(config);
    return upload;
}

void DistanceGpuProbe::setGlossyChain(std::shared_ptr<const CubeChain> chain) const {
    if (glossyChain) return;
    glossyCompressed = chainHasBlocks(*asset, *chain);
    glossyTexture = uploadChainArrays(
        {chain.get()}, glossyCompressed ? ChainBlocks{&asset->glossyBlocks} : ChainBlocks{},
        allocate);
    glossyChain = std::move(chain);
}

std::size_t DistanceGpuProbe::gpuBytes() const {
    const DistanceProbeAsset& a = *asset;
    return (layersUploaded > 0 ? compositeBytes(a) : 0) + tileBytes +
           (a.sky.empty() ? 0 : skyTextureBytes(a.sky)) +
           (glossyChain ? chainArrayBytes(*glossyChain, glossyCompressed) : 0);
}

void DistanceGpuProbe::bindTo(GLuint program, const DistanceBindings& b, bool glossy,
                              const gpu::Texture* ggxAlbedo) const {
    bindSampler(program, "uLayers", b.layers, layers.id());
    if (layerDistance) bindSampler(program, "uLayerDistance", b.layerDistance, layerDistance.id());
    bindSampler(program, "uSky", b.sky, sky.id());
    setIntUniform(program, "uHasSky", sky.id() != 0 ? 1 : 0);
    if (config.features & kFeatureLayers) {
        bindSampler(program, "uTileAtlas", b.tileAtlas, tiles.atlas.id());
        bindSampler(program, "uTileTable", b.tileTable, tiles.table.id());
        glProgramUniform2i(program, glGetUniformLocation(program, "uTileGrid"), tileGrid.x,
                           tileGrid.y);
    }
    params.bind(b.params);
    bindUniformBlock(program, "DistanceParamsUniforms", b.params);
    if (glossy && glossyChain) {
        bindSampler(program, "uChain", b.chain, glossyTexture.id());
        setIntUniform(program, "uChainLevels", int(glossyChain->levels.size()));
        if (ggxAlbedo) bindSampler(program, "uGgxAlbedo", b.ggxAlbedo, ggxAlbedo->id());
    }
}

} // namespace specula
