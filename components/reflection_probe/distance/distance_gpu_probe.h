#pragma once
// A distance probe on the GPU: its textures, lookup configuration and parameter block, and how
// a program that runs the lookup (distance_reflector.frag, or a host's shader with
// distance_host.glsl) is bound to them. Specula's own DistanceStore (system/) and a host's
// DistanceHostProbe both hold one, so the host path binds exactly what the sandbox draws with.
// Needs a current GL 4.5 context.
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/gpu/gl_objects.h"
#include "engine/image/ggx_prefilter.h"

#include <memory>
#include <string>
#include <vector>

namespace specula {

// What is stored on the GPU: the object layers as half floats when they fit. The bench's
// layered rows (quick, 256^2 faces) moved from whole float layers to half tiles by +0.001 dB or
// less (room env 32.536 -> 32.537 dB, truck_room 28.867 -> 28.868 dB, fetches/px unchanged),
// and the tiles take half the memory. The CPU copy (what the twin reads) holds the same
// rounded values.
DistanceProbeAsset storedDistanceAsset(DistanceProbeAsset asset);
LayerTiles storedLayerTiles(const DistanceProbeAsset& stored);

// The defines every distance variant shares: one per method row (features' method bits),
// HAS_GLOSSY, HAS_FRESNEL and HAS_ROUGHNESS_MAP.
std::vector<std::string> distanceFeatureDefines(std::uint32_t features, bool roughnessMap);
// The permutation defines of a feature set (distance_probe.h's bits): one per method row,
// HAS_LAYERS and LAYER_TILES (object layers as tiles), HAS_GLOSSY, HAS_FRESNEL, and
// HAS_ROUGHNESS_MAP. Unused features compile out.
std::vector<std::string> distanceDefines(std::uint32_t features, bool roughnessMap);

// Texture units and the uniform-buffer binding point the lookup reads from.
struct DistanceBindings {
    // (7 is the roughness map's, kRoughnessMapUnit.)
    GLuint layers = 1, sky = 2, chain = 3, ggxAlbedo = 4, tileAtlas = 5, tileTable = 6,
           layerDistance = 8;
    GLuint params = GLuint(glsl::kDistanceParamsBinding); // the block's declared binding
};

struct DistanceGpuProbe {
    std::shared_ptr<const DistanceProbeAsset> asset; // as stored (storedDistanceAsset)
    DistanceLookupConfig config;
    gpu::UniformBuffer<glsl::DistanceParamsBlock> params; // config's block, as the shader reads it
    gpu::Texture layers;                                  // the composite's cube (layer 0)
    // A compressed composite's distances (`layers` then holds its radiance in BC6H).
    gpu::Texture layerDistance;
    int layersUploaded = 0; // layers on the GPU: the composite, or every layer
    // The object layers (1..) as tiles (distance_layer_tiles.h), once layered lookups need
    // them: tile size and tiles per face side.
    LayerTileTextures tiles;
    glm::ivec2 tileGrid{0};
    std::size_t tileBytes = 0;
    gpu::Texture sky;
    // Where the textures come from (engine/gpu/texture_spec.h): the runtime's own, or the
    // host's in the unmanaged mode (DistanceHostOptions::textures).
    gpu::TextureAllocator allocate = gpu::createTexture;
    // The composite's GGX prefiltered chain (glossyChainOf) and its levels 1.. on the GPU
    // (uploadChainArray), once a rough reflector reads it (mutable: Specula's store makes it
    // from hooks that get the probe const).
    mutable std::shared_ptr<const CubeChain> glossyChain;
    mutable gpu::Texture glossyTexture;
    mutable bool glossyCompressed = false; // glossyTexture holds the asset's BC6H blocks

    // The sky's texture; the layers wait for applySettings.
    static DistanceGpuProbe load(std::shared_ptr<const DistanceProbeAsset> stored,
                                 gpu::TextureAllocator allocate = gpu::createTexture);
    // The textures a probe of `stored` allocates under `config`, with `chain` when a rough
    // reflector reads it (setGlossyChain): what a host makes for the unmanaged mode.
    static std::vector<gpu::TextureSpec> textureSpecs(const DistanceProbeAsset& stored,
                                                      const DistanceLookupConfig& config,
                                                      const CubeChain* chain);
    // The lookup configuration of `settings` and its block; uploads the layers the method
    // reads when the textures hold fewer (the composite alone unless layered). Throws Error
    // before any change when the settings do not fit the asset. True when it uploaded textures.
    bool applySettings(const DistanceProbe& settings);
    // Uploads `chain` (the composite's, glossyChainOf) unless the probe has one.
    void setGlossyChain(std::shared_ptr<const CubeChain> chain) const;
    std::size_t gpuBytes() const;
    // Binds the textures and the parameter block on `b`'s units and binding point and points
    // `program`'s samplers and block at them. `glossy`: the chain and `ggxAlbedo` too.
    void bindTo(GLuint program, const DistanceBindings& b, bool glossy,
                const gpu::Texture* ggxAlbedo) const;
};

} // namespace specula
