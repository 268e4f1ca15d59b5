#include "distance_host_probe.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/distance/shaders/distance_params.glsl.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"

namespace specula {

namespace {

constexpr const char* kHostShader =
    "components/reflection_probe/distance/shaders/distance_host.glsl";

// The asset as the GPU probe stores it, its lookup configuration (the settings fit, before
// any GL call) and, for a glossy probe, the chain it uploads.
struct HostInputs {
    std::shared_ptr<const DistanceProbeAsset> stored;
    DistanceLookupConfig config;
    std::shared_ptr<const CubeChain> chain;
};

HostInputs readHostInputs(const std::string& manifestPath, const DistanceHostOptions& options) {
    HostInputs in;
    in.stored = std::make_shared<const DistanceProbeAsset>(
        storedDistanceAsset(readDistanceProbe(manifestPath)));
    in.config = makeLookupConfig(options.settings, *in.stored);
    if (options.glossy) in.chain = std::make_shared<const CubeChain>(glossyChainOf(*in.stored));
    return in;
}

HostLayout layoutOf(const HostInputs& in) {
    HostLayout layout;
    layout.textures = DistanceGpuProbe::textureSpecs(*in.stored, in.config, in.chain.get());
    if (in.chain) layout.textures.push_back(gpu::ggxAlbedoTextureSpec());
    layout.paramsBytes = sizeof(glsl::DistanceParamsBlock);
    return layout;
}

} // namespace

HostLayout DistanceHostProbe::describe(const std::string& manifestPath,
                                       const DistanceHostOptions& options) {
    HostLayout layout;
    try {
        layout = layoutOf(readHostInputs(manifestPath, options));
    } catch (const std::exception& e) {
        layout.error = e.what();
    }
    return layout;
}

DistanceHostProbe::~DistanceHostProbe() = default;

DistanceHostResult DistanceHostProbe::create(const std::string& manifestPath,
                                             const DistanceHostOptions& options) {
    DistanceHostResult result;
    try {
        HostInputs in = readHostInputs(manifestPath, options);
        if (const std::string missing = missingHostGlFeature(in.stored->faceRes, 6);
            !missing.empty())
            throw Error(manifestPath, "", missing);
        // Unmanaged: every host texture is checked before anything is uploaded, so a wrong one
        // leaves the host's textures as they were.
        gpu::TextureAllocator allocate =
            hostAllocator(options.unmanaged, layoutOf(in), manifestPath);

        std::unique_ptr<DistanceHostProbe> probe(new DistanceHostProbe);
        probe->options_ = options;
        probe->gpu_ = DistanceGpuProbe::load(std::move(in.stored), allocate);
        if (options.unmanaged.paramsBuffer != 0)
            probe->gpu_.params = gpu::UniformBuffer<glsl::DistanceParamsBlock>::borrow(
                options.unmanaged.paramsBuffer);
        probe->gpu_.applySettings(options.settings);
        std::uint32_t features = probe->gpu_.config.features;
        if (in.chain) {
            probe->gpu_.setGlossyChain(std::move(in.chain));
            probe->ggxAlbedo_ = gpu::createGgxAlbedoTexture(allocate);
            features |= kFeatureGlossy;
        }
        probe->library_ = hostGlslLibrary(kHostShader, distanceDefines(features, false));
        throwOnHostGlError(manifestPath);
        result.probe = std::move(probe);
    } catch (const std::exception& e) { // Error, or bad_alloc for a probe too large to hold
        result.error = e.what();
    }
    return result;
}

void DistanceHostProbe::bindTo(GLuint program) const {
    gpu_.bindTo(program, options_.bindings, options_.glossy, &ggxAlbedo_);
}

} // namespace specula
