#pragma once
// The GPU side of levels of distance probes (distance_level.h): a level's probes' composites
// in one texture array, their lookups and volumes in one uniform block, one shader variant
// per method, K, blend and output. Each reflector draw passes the probes whose influence
// volume meets the reflector's bounds; each pixel blends up to K of them
// (shaders/distance_level_reflector.frag). A rough reflector (issue 14) also reads every
// probe's GGX chain: made and uploaded by the first sync that finds one, never otherwise.
#include "components/reflection_probe/distance/distance_level.h"
#include "components/reflection_probe/distance/distance_level_gpu.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/probe_volume.h"
#include "components/reflection_probe/shader_variants.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "engine/core/glsl_host.h"
#include "engine/gpu/gl_objects.h"
#include "engine/image/ggx_prefilter.h"

#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

namespace specula {
// The store holds the runtime's DistanceLevelGpu (distance_level_gpu.h), as a host's
// DistanceLevelHostProbe does.

struct DistanceLevelVariant {
    std::uint32_t features = 0; // the method's bit, kFeatureGlossy and kFeatureFresnel
    int k = 4;
    int blend = 2;
    int output = 0;
    bool roughnessMap = false; // a glossy reflector's HAS_ROUGHNESS_MAP (usesRoughnessMap)

    auto operator<=>(const DistanceLevelVariant&) const = default;
    DistanceLevelVariant filter() const;
    std::string name() const;
    gpu::Program build() const;
};

class DistanceLevelStore final : public FlavourStoreBase<DistanceLevel, DistanceLevelGpu> {
public:
    std::string_view flavour() const override { return "distance-level"; }
    std::string_view settingsName() const override { return "DistanceLevel"; }

    // Makes the glossy chains of every level a rough reflector reads.
    void syncReflectors(ecs::Registry& registry, ProbeFrameStats& stats) override;
    // The chains a synced level's rough reflectors read (empty before one did; blend order,
    // as DistanceLevelGpu::volumes): what the CPU twin reads too.
    const std::vector<std::shared_ptr<const CubeChain>>* glossyChains(ecs::Entity level) const;

private:
    DistanceLevelGpu loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) override;
    void applySettings(DistanceLevelGpu& level, const DistanceLevel& settings,
                       ProbeFrameStats& stats) override;
    std::size_t gpuBytesOf(const DistanceLevelGpu& level) const override;
    void drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector, const Reflector& r,
                       const DistanceLevelGpu& level, const DistanceLevel& settings) override;

    // The level's chains and their texture, unless it has them.
    void prepareGlossy(const DistanceLevelGpu& level, ProbeFrameStats& stats);

    SharedAssets<DistanceProbeAsset> assets_;
    gpu::Texture ggxAlbedo_; // E(n.v, roughness) for rough reflectors, made with a chain
    ShaderVariants<DistanceLevelVariant> variants_;
    std::unordered_set<ecs::Entity> warnedOutside_;
};

} // namespace specula
