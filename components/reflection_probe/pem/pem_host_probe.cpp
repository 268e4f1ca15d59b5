#include "pem_host_probe.h"

#include "engine/core/error.h"

namespace specula {

namespace {
constexpr const char* kHostShader = "components/reflection_probe/pem/shaders/pem_host.glsl";
} // namespace

PemHostProbe::~PemHostProbe() = default;

PemHostResult PemHostProbe::create(const std::string& manifestPath, const PemHostOptions& options) {
    PemHostResult result;
    try {
        auto asset = std::make_shared<const PemAsset>(readPemProbe(manifestPath));
        if (const std::string missing =
                missingHostGlFeature(asset->faceRes, 6 * int(asset->samples.size()));
            !missing.empty())
            throw Error(manifestPath, "", missing);
        const bool distance = asset->distance != nullptr, mip = asset->mipLevels > 1;
        std::unique_ptr<PemHostProbe> probe(new PemHostProbe);
        probe->options_ = options;
        probe->gpu_ = PemGpuProbe::load(std::move(asset));
        probe->gpu_.applySettings(options.settings);
        probe->library_ = hostGlslLibrary(
            kHostShader, {std::string("GEOMETRY_DISTANCE=") + (distance ? "1" : "0"),
                          std::string("PEM_MIP=") + (mip ? "1" : "0")});
        throwOnHostGlError(manifestPath);
        result.probe = std::move(probe);
    } catch (const std::exception& e) { // Error, or bad_alloc for a probe too large to hold
        result.error = e.what();
    }
    return result;
}

void PemHostProbe::setSettings(const PemProbe& settings) {
    options_.settings = settings;
    gpu_.applySettings(settings);
}

void PemHostProbe::bindTo(GLuint program) const {
    gpu_.bindTo(program, options_.bindings, false);
}

} // namespace specula
