#pragma once
// The GPU side of distance-cubemap probes: the cooked cube layers and sky as textures, the
// lookup parameters as one uniform block, one shader variant per feature set.
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/flavour_store_base.h"
#include "components/reflection_probe/shader_variants.h"
#include "engine/gpu/gl_objects.h"

#include <memory>
#include <string>
#include <unordered_map>

namespace specula {

struct DistanceProbeGpu {
    std::shared_ptr<const DistanceProbeAsset> asset;
    DistanceLookupConfig config;
    gpu::UniformBuffer<glsl::DistanceParamsBlock> params; // config's block, as the shader reads it
    gpu::Texture layers;
    int layersUploaded = 0; // cube layers in `layers`: the composite, or every layer
    gpu::Texture sky;
};

// A compiled feature set: the methods' bits, layers and Fresnel, and the output.
struct DistanceVariant {
    std::uint32_t features = 0;
    int output = 0;

    auto operator<=>(const DistanceVariant&) const = default;
    // The twin-input outputs (1, 2) write no colour, so Fresnel is irrelevant to them.
    DistanceVariant filter() const;
    std::string name() const { return distanceFeatureName(features); }
    gpu::Program build() const;
};

class DistanceStore final : public FlavourStoreBase<DistanceProbe, DistanceProbeGpu> {
public:
    std::string_view flavour() const override { return "distance"; }
    std::string_view settingsName() const override { return "DistanceProbe"; }

    // The CPU-side asset and lookup configuration of a synced probe (null if none).
    const DistanceProbeAsset* asset(ecs::Entity probe) const;
    const DistanceLookupConfig* config(ecs::Entity probe) const;

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
    ShaderVariants<DistanceVariant> variants_;
};

} // namespace specula
