#pragma once
// The GPU side of distance-cubemap probes: the cooked cube layers and sky as textures, the
// lookup parameters as one uniform block, one shader variant per feature set.
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "components/reflection_probe/shader_variants.h"
#include "engine/gpu/gl_objects.h"
#include "engine/image/ggx_prefilter.h"

#include <memory>
#include <string>
#include <unordered_map>

namespace specula {

struct DistanceProbeGpu {
    std::shared_ptr<const DistanceProbeAsset> asset;
    DistanceLookupConfig config;
    gpu::UniformBuffer<glsl::DistanceParamsBlock> params; // config's block, as the shader reads it
    gpu::Texture layers;                                  // the composite's cube (layer 0)
    int layersUploaded = 0; // layers on the GPU: the composite, or every layer
    // The object layers (1..) as tiles (distance_layer_tiles.h), once layered lookups need
    // them: tile size and tiles per face side.
    LayerTileTextures tiles;
    glm::ivec2 tileGrid{0};
    std::size_t tileBytes = 0;
    gpu::Texture sky;
    // The composite's GGX prefiltered chain (glossyChainOf) and its levels 1.. on the GPU
    // (uploadChainArray): made by the first sync that finds a rough reflector of this probe,
    // since only rough reflectors read it (mutable: the store's hooks get the probe const).
    mutable std::shared_ptr<const CubeChain> glossyChain;
    mutable gpu::Texture glossyTexture;
};

// The asset as a distance store holds it: the object layers rounded to half floats when they
// fit (their atlas is then RGBA16F), so that the CPU twin reads what the GPU does.
DistanceProbeAsset storedDistanceAsset(DistanceProbeAsset asset);
// The object layers' tiles as the store uploads them for a layered lookup, of an asset as
// storedDistanceAsset gives it.
LayerTiles storedLayerTiles(const DistanceProbeAsset& stored);

// A compiled feature set: the methods' bits, layers, glossy and Fresnel, whether a glossy
// reflector reads a roughness map (HAS_ROUGHNESS_MAP; usesRoughnessMap), and the output.
struct DistanceVariant {
    std::uint32_t features = 0;
    int output = 0;
    bool roughnessMap = false;

    auto operator<=>(const DistanceVariant&) const = default;
    // The twin-input outputs (1 to 4) write no colour, so Fresnel, glossy and the roughness
    // map are irrelevant to them; the map is irrelevant without glossy.
    DistanceVariant filter() const;
    std::string name() const;
    gpu::Program build() const;
};

class DistanceStore final : public FlavourStoreBase<DistanceProbe, DistanceProbeGpu> {
public:
    std::string_view flavour() const override { return "distance"; }
    std::string_view settingsName() const override { return "DistanceProbe"; }

    // Makes the glossy chain of every probe a rough reflector reads.
    void syncReflectors(ecs::Registry& registry, ProbeFrameStats& stats) override;

    // The CPU-side asset and lookup configuration of a synced probe (null if none).
    const DistanceProbeAsset* asset(ecs::Entity probe) const;
    const DistanceLookupConfig* config(ecs::Entity probe) const;
    // The glossy chain a synced probe's rough reflectors read (null before one drew): what
    // the CPU twin needs (CpuDistanceProbe's `glossy`).
    std::shared_ptr<const CubeChain> glossyChain(ecs::Entity probe) const;

private:
    DistanceProbeGpu loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) override;
    void applySettings(DistanceProbeGpu& probe, const DistanceProbe& settings,
                       ProbeFrameStats& stats) override;
    std::size_t gpuBytesOf(const DistanceProbeGpu& probe) const override;
    void drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector, const Reflector& r,
                       const DistanceProbeGpu& probe, const DistanceProbe& settings) override;

    // Probes that share an asset share its CPU copy; the GPU copy is per probe since the
    // methods (and so the layers uploaded) may differ.
    SharedAssets<DistanceProbeAsset> assets_;
    // Probes that share an asset share its chain (prefiltered once). An entry counts only
    // while its asset is the very one alive (a freed asset's address may come back).
    struct SharedChain {
        std::weak_ptr<const DistanceProbeAsset> asset;
        std::weak_ptr<const CubeChain> chain;
    };
    std::unordered_map<const DistanceProbeAsset*, SharedChain> chains_;
    std::shared_ptr<const CubeChain> chainOf(const std::shared_ptr<const DistanceProbeAsset>& a);
    // The probe's glossy chain and its texture, unless it has them.
    void prepareGlossy(const DistanceProbeGpu& probe, ProbeFrameStats& stats);
    gpu::Texture ggxAlbedo_; // E(n.v, roughness) for rough reflectors, made with a chain
    ShaderVariants<DistanceVariant> variants_;
};

} // namespace specula
