#pragma once
// Specula's own parameterized-environment-map probes: one PemGpuProbe each (the runtime's, as a
// host's PemHostProbe holds; with PemProbeCpu(*asset, params) the twin of what the shader draws
// now), the shader variants and each layered reflector's hull flags.
#include "components/reflection_probe/pem/pem_gpu_probe.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/pem/system/pem_hull.h"
#include "components/reflection_probe/shader_variants.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "engine/gpu/gl_objects.h"

#include <memory>
#include <string>
#include <unordered_map>

namespace specula {

struct PemVariant {
    bool fresnel = false;
    int output = 0;
    bool distance = false; // distance geometry (GEOMETRY_DISTANCE), else box
    bool local = false;    // a local layer over the distant one (HAS_LOCAL_LAYER)
    bool mip = false;      // distant maps with MIP levels, read trilinear (PEM_MIP)

    auto operator<=>(const PemVariant&) const = default;
    // The twin-input outputs (1 to 4) write no colour, so Fresnel is irrelevant to them.
    PemVariant filter() const { return {fresnel && output == 0, output, distance, local, mip}; }
    std::string name() const {
        return std::string(distance ? "pem-distance" : "pem") + (local ? "+local" : "") +
               (mip ? "+mip" : "") + (fresnel ? "+fresnel" : "");
    }
    gpu::Program build() const;
};

class PemStore final : public FlavourStoreBase<PemProbe, PemGpuProbe> {
public:
    std::string_view flavour() const override { return "pem"; }
    std::string_view settingsName() const override { return "PemProbe"; }

private:
    PemGpuProbe loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) override;
    void applySettings(PemGpuProbe& probe, const PemProbe& settings,
                       ProbeFrameStats& stats) override;
    std::size_t gpuBytesOf(const PemGpuProbe& probe) const override;
    void drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector, const Reflector& r,
                       const PemGpuProbe& probe, const PemProbe& settings) override;

    // The reflector's hull flags as a storage buffer, made on its first layered draw and
    // again when its mesh changes (`meshes` holds the primitives' data it was made from).
    struct HullBuffer {
        std::vector<const MeshData*> meshes;
        PemHullFlags flags;
        gpu::Buffer buffer;
    };
    const HullBuffer& hullBuffer(ecs::Entity reflector, const Mesh& mesh);

    // Probes that share an asset share its CPU copy; each holds its own texture.
    SharedAssets<PemAsset> assets_;
    ShaderVariants<PemVariant> variants_;
    std::unordered_map<ecs::Entity, HullBuffer> hulls_;
};

} // namespace specula
