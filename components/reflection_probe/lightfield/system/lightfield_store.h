#pragma once
// Specula's own light-field-slab probes: one LightFieldGpuProbe each (the runtime's, as a
// host's LightFieldHostProbe holds), the environment drawn from the slabs on request, and a
// warning when a reflector leaves the cell the light field is exact in.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/lightfield_gpu_probe.h"
#include "components/reflection_probe/lightfield/lightfield_probe.h"
#include "components/reflection_probe/shader_variants.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "engine/gpu/gl_objects.h"

#include <array>
#include <memory>
#include <string>
#include <unordered_map>
#include <unordered_set>

namespace specula {

struct LightFieldVariant {
    bool fresnel = false;
    bool background = false; // the full-screen environment pass
    bool glossy = false;     // a rough reflector (GLOSSY: shaders/lightfield_glossy.glsl.h)
    int output = 0;
    bool roughnessMap = false; // with glossy: HAS_ROUGHNESS_MAP (usesRoughnessMap)

    auto operator<=>(const LightFieldVariant&) const = default;
    // The background pass and the twin-input outputs write no reflector colour: no Fresnel,
    // no glossy lookup, no roughness map.
    LightFieldVariant filter() const;
    std::string name() const;
    gpu::Program build() const;
};

class LightFieldStore final : public FlavourStoreBase<LightFieldProbe, LightFieldGpuProbe> {
public:
    std::string_view flavour() const override { return "lightfield"; }
    std::string_view settingsName() const override { return "LightFieldProbe"; }

    // The cooked asset of a synced probe (null if none) and the disparities its shader uses
    // now (the settings' override when set, else the cooked per-slab values).
    const LightFieldAsset* asset(ecs::Entity probe) const;
    std::array<float, 6> disparities(ecs::Entity probe) const;

    void drawBackground(const ProbeDrawContext& ctx) override;
    // Uploads the roughness maps of the probes' rough reflectors (outside the timed pass).
    void syncReflectors(ecs::Registry& registry, ProbeFrameStats& stats) override {
        syncRoughnessMaps(registry, stats);
    }

private:
    LightFieldGpuProbe loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) override;
    void applySettings(LightFieldGpuProbe&, const LightFieldProbe&, ProbeFrameStats&) override {
        // disparity and background are uniforms and a pass set at draw time: nothing to do
    }
    std::size_t gpuBytesOf(const LightFieldGpuProbe& probe) const override;
    void drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector, const Reflector& r,
                       const LightFieldGpuProbe& probe, const LightFieldProbe& settings) override;

    void checkCell(const ProbeDrawContext& ctx, ecs::Entity reflector, const LightFieldGpuProbe& p);
    // The atlas's mips and the GGX albedo table, made when a rough reflector first needs them.
    void prepareGlossy(const ProbeDrawContext& ctx, const LightFieldGpuProbe& p);

    SharedAssets<LightFieldAsset> assets_;
    std::unordered_set<ecs::Entity> warnedOutside_; // reflectors already logged as outside
    gpu::VertexArray emptyVao_;                     // the background pass draws no attributes
    gpu::Texture ggxAlbedo_;                        // E(n.v, roughness), made on first use
    ShaderVariants<LightFieldVariant> variants_;
};

} // namespace specula
