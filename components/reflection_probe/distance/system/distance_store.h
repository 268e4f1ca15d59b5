#pragma once
// The GPU side of distance-cubemap probes: the cooked cube layers and sky as textures, the
// lookup parameters as one uniform block, one shader variant per feature set.
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/shader_variants.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "engine/gpu/gl_objects.h"
#include "engine/image/ggx_prefilter.h"

#include <memory>
#include <string>
#include <unordered_map>

namespace specula {

// Specula's own store holds the runtime's GPU probe, as a host's DistanceHostProbe does.
using DistanceProbeGpu = DistanceGpuProbe;

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
