#include "distance_host_probe.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"

namespace specula {

namespace {
constexpr const char* kHostShader =
    "components/reflection_probe/distance/shaders/distance_host.glsl";
} // namespace

DistanceHostProbe::~DistanceHostProbe() = default;

DistanceHostResult DistanceHostProbe::create(const std::string& manifestPath,
                                             const DistanceHostOptions& options) {
    DistanceHostResult result;
    try {
        auto stored = std::make_shared<const DistanceProbeAsset>(
            storedDistanceAsset(readDistanceProbe(manifestPath)));
        makeLookupConfig(options.settings, *stored); // the settings fit, before any GL call
        if (const std::string missing = missingHostGlFeature(stored->faceRes, 6); !missing.empty())
            throw Error(manifestPath, "", missing);
        std::shared_ptr<const CubeChain> chain;
        if (options.glossy) chain = std::make_shared<const CubeChain>(glossyChainOf(*stored));

        std::unique_ptr<DistanceHostProbe> probe(new DistanceHostProbe);
        probe->options_ = options;
        probe->gpu_ = DistanceGpuProbe::load(std::move(stored));
        probe->gpu_.applySettings(options.settings);
        std::uint32_t features = probe->gpu_.config.features;
        if (chain) {
            probe->gpu_.setGlossyChain(std::move(chain));
            probe->ggxAlbedo_ = gpu::createGgxAlbedoTexture();
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
