#include "distance_level_host_probe.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
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

// The level's index and every probe it lists, read and checked before any GL call.
struct LevelInputs {
    LevelIndex index;
    std::map<std::string, std::shared_ptr<const DistanceProbeAsset>> read;
    int faceRes = 0;
};

LevelInputs readLevelInputs(const std::string& indexPath, const DistanceLevelHostOptions& options) {
    LevelInputs in;
    in.index = readLevelIndex(indexPath);
    validateDistanceLevel(options.settings, indexPath);
    const std::filesystem::path dir = std::filesystem::path(indexPath).parent_path();
    for (const LevelProbeEntry& e : in.index.probes) {
        const std::string path = (dir / e.folder / "manifest.json").string();
        in.read[path] = std::make_shared<const DistanceProbeAsset>(readDistanceProbe(path));
        in.faceRes = std::max(in.faceRes, in.read[path]->faceRes);
    }
    return in;
}

// What the level allocates: its textures (in the index's order; the specs do not depend on the
// blend order), the chains' when glossy, the GGX albedo, the parameter block.
HostLayout layoutOf(const LevelInputs& in, const std::string& indexPath,
                    const DistanceLevelHostOptions& options) {
    std::vector<std::shared_ptr<const DistanceProbeAsset>> assets;
    for (const auto& [path, asset] : in.read)
        assets.push_back(asset);
    if (assets.empty()) throw Error(indexPath, "probes", "the level has no probe");
    std::vector<std::shared_ptr<const CubeChain>> chains;
    if (options.glossy)
        for (const auto& a : assets)
            chains.push_back(std::make_shared<const CubeChain>(glossyChainOf(*a)));
    HostLayout layout;
    layout.textures = DistanceLevelGpu::textureSpecs(assets, options.glossy ? &chains : nullptr);
    if (options.glossy) layout.textures.push_back(gpu::ggxAlbedoTextureSpec());
    layout.paramsBytes = sizeof(glsl::LevelParamsBlock);
    return layout;
}

} // namespace

HostLayout DistanceLevelHostProbe::describe(const std::string& indexPath,
                                            const DistanceLevelHostOptions& options) {
    HostLayout layout;
    try {
        layout = layoutOf(readLevelInputs(indexPath, options), indexPath, options);
    } catch (const std::exception& e) {
        layout.error = e.what();
    }
    return layout;
}

DistanceLevelHostProbe::~DistanceLevelHostProbe() = default;

DistanceLevelHostResult DistanceLevelHostProbe::create(const std::string& indexPath,
                                                       const DistanceLevelHostOptions& options) {
    DistanceLevelHostResult result;
    try {
        const LevelInputs in = readLevelInputs(indexPath, options);
        const std::string missing =
            missingHostGlFeature(in.faceRes, 6 * int(in.index.probes.size()));
        if (!missing.empty()) throw Error(indexPath, "", missing);
        // Unmanaged: the host's objects checked before anything is uploaded. (A managed level
        // skips the layout: its chains are prefiltered once, below.)
        const gpu::TextureAllocator allocate =
            options.unmanaged.textures.empty() && options.unmanaged.paramsBuffer == 0
                ? gpu::TextureAllocator(gpu::createTexture)
                : hostAllocator(options.unmanaged, layoutOf(in, indexPath, options), indexPath);

        std::unique_ptr<DistanceLevelHostProbe> probe(new DistanceLevelHostProbe);
        probe->options_ = options;
        probe->gpu_ = DistanceLevelGpu::load(
            indexPath, in.index, [&](const std::string& path) { return in.read.at(path); },
            allocate);
        if (options.unmanaged.paramsBuffer != 0)
            probe->gpu_.params =
                gpu::UniformBuffer<glsl::LevelParamsBlock>::borrow(options.unmanaged.paramsBuffer);
        probe->gpu_.applySettings(options.settings);
        std::uint32_t features = probe->gpu_.methodFeature;
        if (options.glossy) {
            probe->gpu_.setChains(probe->gpu_.makeChains());
            probe->ggxAlbedo_ = gpu::createGgxAlbedoTexture(allocate);
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
