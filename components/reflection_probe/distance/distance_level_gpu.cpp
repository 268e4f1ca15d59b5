#include "distance_level_gpu.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/host_probe.h"
#include "engine/core/error.h"

#include <algorithm>
#include <filesystem>
#include <numeric>

namespace specula {
namespace {

// Whether the influence volume reaches into the box (the reflector's world bounds).
bool influenceMeets(const ProbeInfluence& v, const Aabb& box) {
    if (v.shape == ProbeInfluence::Shape::Box) return v.box.overlaps(box);
    const glm::vec3 nearest = glm::clamp(v.centre, box.min, box.max);
    return glm::distance(nearest, v.centre) <= v.radius;
}

glsl::LevelProbeParams levelProbeParams(const ProbeVolume& v, const DistanceLookupConfig& c) {
    glsl::LevelProbeParams p{};
    p.lookup = c.params;
    p.composite = c.layers[0];
    const ProbeInfluence& in = v.influence;
    p.influenceShape = influenceShapeCode(in);
    p.influenceMin = in.box.min;
    p.influenceMax = in.box.max;
    p.influenceCentre = in.centre;
    p.influenceRadius = in.radius;
    p.blendDistance = v.blendDistance;
    return p;
}

} // namespace

int maxLevelProbes() {
    GLint layers = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &layers);
    return std::min(glsl::kMaxLevelProbes, int(layers) / 6);
}

std::vector<std::string> distanceLevelDefines(std::uint32_t features, int k, LevelBlend blend,
                                              bool roughnessMap) {
    std::vector<std::string> defines = distanceFeatureDefines(features, roughnessMap);
    defines.push_back("HAS_LAYERS=0"); // every probe looks up its composite
    defines.push_back(std::string("COMPRESSED_COMPOSITE=") +
                      ((features & kFeatureCompressedComposite) ? "1" : "0"));
    defines.push_back("LEVEL_K=" + std::to_string(k));
    defines.push_back("LEVEL_BLEND=" + std::to_string(int(blend)));
    return defines;
}

namespace {

// The level shader's sampler names (shaders/distance_level_gpu.glsl) on the single probe's
// textures of distance_textures.h.
gpu::TextureSpec named(gpu::TextureSpec spec, const char* name) {
    spec.name = name;
    return spec;
}
gpu::TextureAllocator naming(const gpu::TextureAllocator& allocate, const char* name) {
    return [&allocate, name](const gpu::TextureSpec& spec) { return allocate(named(spec, name)); };
}

bool allCompressed(const std::vector<std::shared_ptr<const DistanceProbeAsset>>& assets) {
    return std::all_of(assets.begin(), assets.end(),
                       [](const auto& a) { return a->compression == DistanceCompression::Bc6h; });
}
bool allHalf(const std::vector<std::shared_ptr<const DistanceProbeAsset>>& assets) {
    return std::all_of(assets.begin(), assets.end(),
                       [](const auto& a) { return a->halfCompositeDistance; });
}
// BC6H when every probe's chain is its asset's compressed levels (one array holds all).
bool chainsOfBlocks(const std::vector<std::shared_ptr<const DistanceProbeAsset>>& assets,
                    const CubeChain& first) {
    return std::all_of(assets.begin(), assets.end(),
                       [&](const auto& a) { return chainHasBlocks(*a, first); });
}

} // namespace

std::vector<gpu::TextureSpec>
DistanceLevelGpu::textureSpecs(const std::vector<std::shared_ptr<const DistanceProbeAsset>>& assets,
                               const std::vector<std::shared_ptr<const CubeChain>>* chains) {
    const int n = assets.front()->faceRes, probes = int(assets.size());
    std::vector<gpu::TextureSpec> specs;
    if (allCompressed(assets)) {
        specs.push_back(named(compressedCubeArraySpec(n, probes), "uLevelLayers"));
        specs.push_back(named(distanceArraySpec(n, probes, allHalf(assets)), "uLevelDistances"));
    } else {
        specs.push_back(named(cubeArraySpec(n, probes), "uLevelLayers"));
    }
    if (!assets.front()->sky.empty()) specs.push_back(skyTextureSpec(assets.front()->sky));
    if (chains && !chains->empty() && chains->front()->levels.size() >= 2)
        specs.push_back(named(
            chainArraySpec(*chains->front(), probes, chainsOfBlocks(assets, *chains->front())),
            "uLevelChain"));
    return specs;
}

DistanceLevelGpu DistanceLevelGpu::load(const std::string& path, const LevelIndex& index,
                                        const DistanceAssetReader& read,
                                        gpu::TextureAllocator allocate) {
    if (index.flavour != "distance")
        throw Error(path, "flavour", "expected \"distance\", got \"" + index.flavour + "\"");
    if (index.probes.empty()) throw Error(path, "probes", "the level has no probe");
    const int limit = maxLevelProbes();
    if (int(index.probes.size()) > limit)
        throw Error(path, "probes",
                    "the level has " + std::to_string(index.probes.size()) +
                        " probes; one view holds at most " + std::to_string(limit) +
                        " (a uniform block of " + std::to_string(glsl::kMaxLevelProbes) +
                        " probes, 6 texture-array layers each): split the level");
    std::vector<std::size_t> order(index.probes.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return blendsBefore(index.probes[a].volume, index.probes[b].volume);
    });
    DistanceLevelGpu g;
    g.indexPath = path;
    g.allocate = std::move(allocate);
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const std::size_t i : order) {
        const LevelProbeEntry& e = index.probes[i];
        g.volumes.push_back(e.volume);
        g.assets.push_back(read((dir / e.folder / "manifest.json").string()));
        checkLevelFaceRes(g.assets.back()->faceRes, g.assets.front()->faceRes, path, i);
    }
    const int n = g.assets.front()->faceRes, probes = int(g.assets.size());
    const bool half = allHalf(g.assets);
    g.compressed = allCompressed(g.assets);
    if (g.compressed) {
        g.halfDistances = half;
        g.composites = createCompressedCubeArray(n, probes, naming(g.allocate, "uLevelLayers"));
        g.distances = createDistanceArray(n, probes, half, naming(g.allocate, "uLevelDistances"));
        for (int i = 0; i < probes; ++i) {
            uploadCompressedCube(g.composites, i, g.assets[std::size_t(i)]->compositeBlocks);
            uploadDistance(g.distances, i, g.assets[std::size_t(i)]->layers.front(), half);
        }
    } else {
        // Probes of both kinds: the compressed ones' decoded values, as their twins read.
        g.composites = createCubeArray(n, probes, naming(g.allocate, "uLevelLayers"));
        for (int i = 0; i < probes; ++i)
            uploadCube(g.composites, i, g.assets[std::size_t(i)]->layers.front());
    }
    // The level is baked under one sky: the first probe's.
    if (!g.assets.front()->sky.empty()) g.sky = uploadSkyTexture(g.assets.front()->sky, g.allocate);
    return g;
}

void DistanceLevelGpu::applySettings(const DistanceLevel& settings) {
    validateDistanceLevel(settings, indexPath);
    glsl::LevelParamsBlock block{};
    std::uint32_t features = 0;
    for (std::size_t i = 0; i < assets.size(); ++i) {
        const DistanceLookupConfig c = makeLookupConfig(settings.lookup, *assets[i]);
        block.probes[i] = levelProbeParams(volumes[i], c);
        // One array holds every probe's composite: compressed only when all are.
        features = c.features & ~kFeatureCompressedComposite;
        if (compressed) features |= kFeatureCompressedComposite;
    }
    methodFeature = features;
    params.upload(block);
}

std::vector<std::shared_ptr<const CubeChain>> DistanceLevelGpu::makeChains() const {
    std::vector<std::shared_ptr<const CubeChain>> made;
    for (const std::shared_ptr<const DistanceProbeAsset>& a : assets) {
        made.push_back(std::make_shared<const CubeChain>(glossyChainOf(*a)));
        if (made.back()->levels.size() != made.front()->levels.size())
            throw Error(indexPath, "probes",
                        "probe '" + volumes[made.size() - 1].name + "' has a glossy chain of " +
                            std::to_string(made.back()->levels.size()) + " levels, probe '" +
                            volumes.front().name + "' one of " +
                            std::to_string(made.front()->levels.size()) +
                            " (one texture array holds every probe's): re-bake the level");
    }
    return made;
}

void DistanceLevelGpu::setChains(std::vector<std::shared_ptr<const CubeChain>> made) const {
    if (!chains.empty()) return;
    std::vector<const CubeChain*> all;
    ChainBlocks blocks;
    for (std::size_t i = 0; i < made.size(); ++i) {
        all.push_back(made[i].get());
        blocks.push_back(&assets[i]->glossyBlocks);
    }
    chainsCompressed = chainsOfBlocks(assets, *made.front());
    chainTexture = uploadChainArrays(all, chainsCompressed ? blocks : ChainBlocks{},
                                     naming(allocate, "uLevelChain"));
    chains = std::move(made);
}

std::size_t DistanceLevelGpu::gpuBytes() const {
    const DistanceProbeAsset& a = *assets.front();
    std::size_t composite = cubeArrayBytes(a.faceRes, int(assets.size()));
    if (compressed) {
        const std::size_t texels = std::size_t(a.faceRes) * std::size_t(a.faceRes) * 6;
        composite = (a.compositeBlocks.size() + texels * (halfDistances ? 2 : 4)) * assets.size();
    }
    return composite + (a.sky.empty() ? 0 : skyTextureBytes(a.sky)) +
           (chains.empty() ? 0
                           : chains.size() * chainArrayBytes(*chains.front(), chainsCompressed));
}

std::vector<GLint> DistanceLevelGpu::candidatesFor(const Aabb& bounds) const {
    std::vector<GLint> candidates;
    for (std::size_t i = 0; i < volumes.size(); ++i)
        if (bounds.empty() || influenceMeets(volumes[i].influence, bounds))
            candidates.push_back(GLint(i));
    return candidates;
}

void DistanceLevelGpu::bindTo(GLuint program, const DistanceLevelBindings& b,
                              const std::vector<GLint>& candidates, bool glossy,
                              const gpu::Texture* ggxAlbedo) const {
    bindSampler(program, "uLevelLayers", b.layers, composites.id());
    if (compressed) bindSampler(program, "uLevelDistances", b.distances, distances.id());
    bindSampler(program, "uSky", b.sky, sky.id());
    setIntUniform(program, "uHasSky", sky.id() != 0 ? 1 : 0);
    setIntUniform(program, "uProbeCount", int(volumes.size()));
    setIntUniform(program, "uCandidateCount", int(candidates.size()));
    if (!candidates.empty())
        glProgramUniform1iv(program, glGetUniformLocation(program, "uCandidates[0]"),
                            GLsizei(candidates.size()), candidates.data());
    params.bind(b.params);
    bindUniformBlock(program, "LevelParamsUniforms", b.params);
    if (glossy && !chains.empty()) {
        bindSampler(program, "uLevelChain", b.chains, chainTexture.id());
        setIntUniform(program, "uChainSlots", chainArraySlots(*chains.front()));
        setIntUniform(program, "uChainLevels", int(chains.front()->levels.size()));
        if (ggxAlbedo) bindSampler(program, "uGgxAlbedo", b.ggxAlbedo, ggxAlbedo->id());
    }
}

} // namespace specula
