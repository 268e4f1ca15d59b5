#include "pem_host_probe.h"

#include "engine/core/error.h"

namespace specula {

namespace {

constexpr const char* kHostShader = "components/reflection_probe/pem/shaders/pem_host.glsl";

// The host library draws the distant layer: no local layer's maps.
HostLayout layoutOf(const PemAsset& a) {
    HostLayout layout;
    layout.textures = {PemGpuProbe::mapsSpec(a, false)};
    if (a.distance) layout.textures.push_back(PemGpuProbe::distanceSpec(*a.distance));
    layout.paramsBytes = sizeof(glsl::PemParams);
    return layout;
}

} // namespace

HostLayout PemHostProbe::describe(const std::string& manifestPath) {
    HostLayout layout;
    try {
        layout = layoutOf(readPemProbe(manifestPath));
    } catch (const std::exception& e) {
        layout.error = e.what();
    }
    return layout;
}

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
        const gpu::TextureAllocator allocate =
            hostAllocator(options.unmanaged, layoutOf(*asset), manifestPath);
        std::unique_ptr<PemHostProbe> probe(new PemHostProbe);
        probe->options_ = options;
        probe->gpu_ = PemGpuProbe::load(std::move(asset), false, allocate);
        if (options.unmanaged.paramsBuffer != 0)
            probe->gpu_.block =
                gpu::UniformBuffer<glsl::PemParams>::borrow(options.unmanaged.paramsBuffer);
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
