#include "distance_host_probe.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"

namespace specula {

namespace {

constexpr const char* kHostShader =
    "components/reflection_probe/distance/shaders/distance_host.glsl";

// Empty when the current context can run the lookup, else why not. Checked before any GL
// object is made, so a refused probe changes nothing.
std::string missingGlFeature(int faceRes) {
    if (glGetString(GL_VERSION) == nullptr) return "no current OpenGL context";
    const int version = epoxy_gl_version();
    if (version < 45)
        return "OpenGL 4.5 needed (direct state access, texture views), the context has " +
               std::to_string(version / 10) + "." + std::to_string(version % 10);
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (faceRes > maxSize)
        return "face_res " + std::to_string(faceRes) + " is over GL_MAX_TEXTURE_SIZE (" +
               std::to_string(maxSize) + ")";
    return {};
}

// The expanded library without its #version line: the host writes its own first.
std::string libraryText(const std::vector<std::string>& defines) {
    const gpu::ExpandedSource expanded =
        gpu::expandShader(gpu::ShaderSource::file(kHostShader), defines);
    const std::size_t eol = expanded.text.find('\n');
    return eol == std::string::npos ? std::string() : expanded.text.substr(eol + 1);
}

} // namespace

DistanceHostProbe::~DistanceHostProbe() = default;

DistanceHostResult DistanceHostProbe::create(const std::string& manifestPath,
                                             const DistanceHostOptions& options) {
    DistanceHostResult result;
    try {
        auto stored = std::make_shared<const DistanceProbeAsset>(
            storedDistanceAsset(readDistanceProbe(manifestPath)));
        makeLookupConfig(options.settings, *stored); // the settings fit, before any GL call
        if (const std::string missing = missingGlFeature(stored->faceRes); !missing.empty())
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
        probe->library_ = libraryText(distanceDefines(features, false));
        if (const GLenum error = glGetError(); error != GL_NO_ERROR)
            throw Error(manifestPath, "",
                        "OpenGL error " + std::to_string(error) + " uploading the probe");
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
