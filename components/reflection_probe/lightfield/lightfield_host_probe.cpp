#include "lightfield_host_probe.h"

#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"

namespace specula {

namespace {

constexpr const char* kHostShader =
    "components/reflection_probe/lightfield/shaders/lightfield_host.glsl";

HostLayout layoutOf(const LightFieldAsset& a, const LightFieldHostOptions& options) {
    HostLayout layout;
    layout.textures = {LightFieldGpuProbe::atlasSpec(a, options.glossy)};
    if (options.glossy) layout.textures.push_back(gpu::ggxAlbedoTextureSpec());
    return layout;
}

} // namespace

HostLayout LightFieldHostProbe::describe(const std::string& manifestPath,
                                         const LightFieldHostOptions& options) {
    HostLayout layout;
    try {
        layout = layoutOf(readLightFieldProbe(manifestPath), options);
    } catch (const std::exception& e) {
        layout.error = e.what();
    }
    return layout;
}

LightFieldHostProbe::~LightFieldHostProbe() = default;

LightFieldHostResult LightFieldHostProbe::create(const std::string& manifestPath,
                                                 const LightFieldHostOptions& options) {
    LightFieldHostResult result;
    try {
        auto asset = std::make_shared<const LightFieldAsset>(readLightFieldProbe(manifestPath));
        if (const std::string missing = missingHostGlFeature(asset->atlasSize(), 6);
            !missing.empty())
            throw Error(manifestPath, "", missing);
        const gpu::TextureAllocator allocate =
            hostAllocator(options.unmanaged, layoutOf(*asset, options), manifestPath);
        std::unique_ptr<LightFieldHostProbe> probe(new LightFieldHostProbe);
        probe->options_ = options;
        probe->gpu_ =
            LightFieldGpuProbe::load(std::move(asset), manifestPath, options.glossy, allocate);
        if (options.glossy) probe->ggxAlbedo_ = gpu::createGgxAlbedoTexture(allocate);
        probe->library_ =
            hostGlslLibrary(kHostShader, {std::string("GLOSSY=") + (options.glossy ? "1" : "0")});
        throwOnHostGlError(manifestPath);
        result.probe = std::move(probe);
    } catch (const std::exception& e) { // Error, or bad_alloc for a probe too large to hold
        result.error = e.what();
    }
    return result;
}

void LightFieldHostProbe::bindTo(GLuint program) const {
    gpu_.bindTo(program, options_.bindings, options_.settings, options_.glossy, &ggxAlbedo_);
}

} // namespace specula
