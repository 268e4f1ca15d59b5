#pragma once
// A probe flavour defined only under tests/: every reflected ray sees one cooked colour. It
// exists to prove that a flavour is one folder -- settings component, manifest read and
// write, parameter block shared by shader and twin, store -- registered with the system by
// one addFlavour() call and drawn with no file outside tests/ edited for it.
#include "components/reflection_probe/manifest_fields.h"
#include "components/reflection_probe/shader_variants.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/glsl_host.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/shader.h"

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

namespace specula::glsl {
#include "tests/probe/constant_flavour/constant_params.glsl.h"
} // namespace specula::glsl

namespace specula::test {

// The settings component.
struct ConstantProbe {
    float gain = 1.f;
    bool operator==(const ConstantProbe&) const = default;
};

struct ConstantAsset {
    glm::vec3 colour{0.f};
};

inline void writeConstantProbe(const ConstantAsset& a, const std::string& dir) {
    writeProbeFolder(dir, "constant-colour test", [&](const std::filesystem::path&) {
        nlohmann::json manifest = probeManifestHeader("constant", "", ProbeInputs{});
        manifest["colour"] = vec3Json(a.colour);
        return manifest;
    });
}

inline ConstantAsset readConstantProbe(const ProbeManifest& m) {
    const ManifestFields r{m.path};
    ConstantAsset a;
    a.colour = r.vec3(m.json, "colour", "", 1e4f);
    return a;
}

// The C++ twin of the lookup: the shared code on the block the store uploads.
inline glm::vec3 constantTwin(const glsl::ConstantParams& p) {
    return glsl::constantRadiance(p);
}

struct ConstantProbeGpu {
    ConstantAsset asset;
    glsl::ConstantParams params{};
    gpu::UniformBuffer<glsl::ConstantParams> block;
};

struct ConstantVariant {
    bool fresnel = false;
    int output = 0;
    auto operator<=>(const ConstantVariant&) const = default;
    ConstantVariant filter() const { return {fresnel && output == 0, output}; }
    std::string name() const { return fresnel ? "constant+fresnel" : "constant"; }
    gpu::Program build() const {
        return gpu::buildProgram(
            gpu::ShaderSource::file("components/reflection_probe/shaders/reflector.vert"),
            gpu::ShaderSource::file("tests/probe/constant_flavour/constant_reflector.frag"),
            {std::string("HAS_FRESNEL=") + (fresnel ? "1" : "0"),
             "OUTPUT=" + std::to_string(output)});
    }
};

class ConstantStore final : public FlavourStoreBase<ConstantProbe, ConstantProbeGpu> {
public:
    std::string_view flavour() const override { return "constant"; }
    std::string_view settingsName() const override { return "ConstantProbe"; }

    const glsl::ConstantParams* params(ecs::Entity e) const {
        const ConstantProbeGpu* g = probe(e);
        return g ? &g->params : nullptr;
    }

private:
    ConstantProbeGpu loadProbe(const ProbeManifest& m, ProbeFrameStats&) override {
        ConstantProbeGpu g;
        g.asset = readConstantProbe(m);
        return g;
    }
    void applySettings(ConstantProbeGpu& g, const ConstantProbe& s,
                       ProbeFrameStats& stats) override {
        g.params = {g.asset.colour, s.gain};
        g.block.upload(g.params);
        ++stats.parameterUploads;
    }
    std::size_t gpuBytesOf(const ConstantProbeGpu&) const override {
        return sizeof(glsl::ConstantParams);
    }
    void drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector, const Reflector& r,
                       const ConstantProbeGpu& g, const ConstantProbe&) override {
        const ConstantVariant v{r.fresnelF0 >= 0.f, ctx.output};
        gpu::Program& prog = variants_.get(v);
        ctx.stats.drew(v.filter().name());
        prog.use();
        SceneRenderer::setCameraUniforms(prog, ctx.camera);
        g.block.bind(glsl::kConstantParamsBinding);
        prog.setUniform("uF0", r.fresnelF0);
        ctx.scene.drawEntity(reflector, prog);
    }

    ShaderVariants<ConstantVariant> variants_;
};

} // namespace specula::test
