#include "distance_level_host_probe.h"

#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

namespace specula {

namespace {
constexpr const char* kHostShader =
    "components/reflection_probe/distance/shaders/distance_level_host.glsl";
} // namespace

DistanceLevelHostProbe::~DistanceLevelHostProbe() = default;

DistanceLevelHostResult DistanceLevelHostProbe::create(const std::string& indexPath,
                                                       const DistanceLevelHostOptions& options) {
    DistanceLevelHostResult result;
    try {
        const LevelIndex index = readLevelIndex(indexPath);
        validateDistanceLevel(options.settings, indexPath);
        // Every probe read and checked before any GL call (the first probe's size decides).
        std::map<std::string, std::shared_ptr<const DistanceProbeAsset>> read;
        const std::filesystem::path dir = std::filesystem::path(indexPath).parent_path();
        int faceRes = 0;
        for (const LevelProbeEntry& e : index.probes) {
            const std::string path = (dir / e.folder / "manifest.json").string();
            read[path] = std::make_shared<const DistanceProbeAsset>(readDistanceProbe(path));
            faceRes = std::max(faceRes, read[path]->faceRes);
        }
        const std::string missing = missingHostGlFeature(faceRes, 6 * int(index.probes.size()));
        if (!missing.empty()) throw Error(indexPath, "", missing);

        std::unique_ptr<DistanceLevelHostProbe> probe(new DistanceLevelHostProbe);
        probe->options_ = options;
        probe->gpu_ = DistanceLevelGpu::load(
            indexPath, index, [&](const std::string& path) { return read.at(path); });
        probe->gpu_.applySettings(options.settings);
        std::uint32_t features = probe->gpu_.methodFeature;
        if (options.glossy) {
            probe->gpu_.setChains(probe->gpu_.makeChains());
            probe->ggxAlbedo_ = gpu::createGgxAlbedoTexture();
            features |= kFeatureGlossy;
        }
        probe->library_ =
            hostGlslLibrary(kHostShader, distanceLevelDefines(features, options.settings.k,
                                                              options.settings.blend, false));
        throwOnHostGlError(indexPath);
        result.probe = std::move(probe);
    } catch (const std::exception& e) { // Error, or bad_alloc for a level too large to hold
        result.error = e.what();
    }
    return result;
}

void DistanceLevelHostProbe::bindTo(GLuint program, const Aabb& reflectorBounds) const {
    gpu_.bindTo(program, options_.bindings, gpu_.candidatesFor(reflectorBounds), options_.glossy,
                &ggxAlbedo_);
}

} // namespace specula
