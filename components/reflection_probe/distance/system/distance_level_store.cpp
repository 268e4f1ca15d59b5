#include "distance_level_store.h"

#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/level_index.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"
#include "engine/log/log.h"
#include "engine/scene/mesh_bounds.h"

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

DistanceLevelVariant DistanceLevelVariant::filter() const {
    DistanceLevelVariant v = *this;
    if (v.output != 0) v.features &= ~kFeatureFresnel;
    // OUTPUT 1, 2 and 4 (TEXCOORD_0) write no colour; 3 (|n.v|) is the glossy twin's input.
    if (v.output == 1 || v.output == 2 || v.output == 4) v.features &= ~kFeatureGlossy;
    if (!(v.features & kFeatureGlossy)) v.roughnessMap = false;
    return v;
}

std::string DistanceLevelVariant::name() const {
    return "level " + distanceFeatureName(features) + (roughnessMap ? "+roughness-map" : "") +
           " k" + std::to_string(k) + " " + toString(LevelBlend(blend));
}

gpu::Program DistanceLevelVariant::build() const {
    auto bit = [&](std::uint32_t b) { return (features & b) ? "1" : "0"; };
    std::vector<std::string> defines;
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.define) defines.push_back(std::string(row.define) + "=" + bit(row.feature));
    defines.push_back("HAS_LAYERS=0");
    defines.push_back(std::string("HAS_GLOSSY=") + bit(kFeatureGlossy));
    defines.push_back(std::string("HAS_ROUGHNESS_MAP=") + (roughnessMap ? "1" : "0"));
    defines.push_back(std::string("HAS_FRESNEL=") + bit(kFeatureFresnel));
    defines.push_back("LEVEL_K=" + std::to_string(k));
    defines.push_back("LEVEL_BLEND=" + std::to_string(blend));
    defines.push_back("OUTPUT=" + std::to_string(output));
    return gpu::buildProgram(
        gpu::ShaderSource::file("components/reflection_probe/shaders/reflector.vert"),
        gpu::ShaderSource::file(
            "components/reflection_probe/distance/shaders/distance_level_reflector.frag"),
        defines);
}

DistanceLevelGpu DistanceLevelStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats&) {
    const std::string& path = manifest.path;
    const LevelIndex index = levelIndexFromJson(manifest.json, path);
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
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    for (const std::size_t i : order) {
        const LevelProbeEntry& e = index.probes[i];
        const std::string manifestPath = (dir / e.folder / "manifest.json").string();
        g.volumes.push_back(e.volume);
        g.assets.push_back(
            assets_.get(manifestPath, [&] { return readDistanceProbe(manifestPath); }));
        if (g.assets.back()->faceRes != g.assets.front()->faceRes)
            throw Error(path, "probes[" + std::to_string(i) + "]",
                        "face resolution " + std::to_string(g.assets.back()->faceRes) +
                            " differs from the level's " +
                            std::to_string(g.assets.front()->faceRes) +
                            " (one texture array holds every probe): re-bake the level");
    }
    g.composites = createCubeArray(g.assets.front()->faceRes, int(g.assets.size()));
    for (std::size_t i = 0; i < g.assets.size(); ++i)
        uploadCube(g.composites, int(i), g.assets[i]->layers.front());
    // The level is baked under one sky: the first probe's.
    if (!g.assets.front()->sky.empty()) g.sky = uploadSkyTexture(g.assets.front()->sky);
    return g;
}

void DistanceLevelStore::applySettings(DistanceLevelGpu& g, const DistanceLevel& settings,
                                       ProbeFrameStats& stats) {
    validateDistanceLevel(settings, g.indexPath);
    glsl::LevelParamsBlock block{};
    std::uint32_t features = 0;
    for (std::size_t i = 0; i < g.assets.size(); ++i) {
        const DistanceLookupConfig c = makeLookupConfig(settings.lookup, *g.assets[i]);
        block.probes[i] = levelProbeParams(g.volumes[i], c);
        features = c.features;
    }
    g.methodFeature = features;
    g.params.upload(block);
    ++stats.parameterUploads;
}

std::size_t DistanceLevelStore::gpuBytesOf(const DistanceLevelGpu& g) const {
    const DistanceProbeAsset& a = *g.assets.front();
    return cubeArrayBytes(a.faceRes, int(g.assets.size())) +
           (a.sky.empty() ? 0 : skyTextureBytes(a.sky)) +
           (g.chains.empty() ? 0 : g.chains.size() * chainArrayBytes(*g.chains.front()));
}

void DistanceLevelStore::syncReflectors(ecs::Registry& registry, ProbeFrameStats& stats) {
    registry.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
        if (!(r.roughness > 0.f)) return;
        if (const DistanceLevelGpu* g = probe(r.probe)) prepareGlossy(*g, stats);
    });
    syncRoughnessMaps(registry, stats);
}

void DistanceLevelStore::prepareGlossy(const DistanceLevelGpu& g, ProbeFrameStats& stats) {
    if (!g.chains.empty()) return;
    // Every chain made and checked before any is kept (throws before any change).
    std::vector<std::shared_ptr<const CubeChain>> chains;
    std::vector<const CubeChain*> all;
    for (const std::shared_ptr<const DistanceProbeAsset>& a : g.assets) {
        chains.push_back(std::make_shared<const CubeChain>(glossyChainOf(*a)));
        all.push_back(chains.back().get());
        if (chains.back()->levels.size() != chains.front()->levels.size())
            throw Error(g.indexPath, "probes",
                        "probe '" + g.volumes[chains.size() - 1].name + "' has a glossy chain of " +
                            std::to_string(chains.back()->levels.size()) + " levels, probe '" +
                            g.volumes.front().name + "' one of " +
                            std::to_string(chains.front()->levels.size()) +
                            " (one texture array holds every probe's): re-bake the level");
    }
    g.chainTexture = uploadChainArrays(all);
    g.chains = std::move(chains);
    // The albedo table every rough reflector reads, made with the first chains (one upload).
    if (!ggxAlbedo_) ggxAlbedo_ = gpu::createGgxAlbedoTexture();
    ++stats.textureUploads;
}

const std::vector<std::shared_ptr<const CubeChain>>*
DistanceLevelStore::glossyChains(ecs::Entity e) const {
    const DistanceLevelGpu* g = probe(e);
    return g ? &g->chains : nullptr;
}

void DistanceLevelStore::drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                       const Reflector& r, const DistanceLevelGpu& g,
                                       const DistanceLevel& settings) {
    // The probes whose influence meets the reflector, in blend order: each pixel walks only
    // those. A reflector with no bounds gets every probe.
    const Aabb bounds = meshWorldBoundsConservative(ctx.registry, reflector);
    std::vector<GLint> candidates;
    for (std::size_t i = 0; i < g.volumes.size(); ++i)
        if (bounds.empty() || influenceMeets(g.volumes[i].influence, bounds))
            candidates.push_back(GLint(i));
    if (candidates.empty() && warnedOutside_.insert(reflector).second)
        log().warn("a reflector lies outside every influence volume of the level {}: the "
                   "probe nearest to each pixel answers there",
                   g.indexPath);

    DistanceLevelVariant v{g.methodFeature, settings.k, int(settings.blend), ctx.output,
                           usesRoughnessMap(r)};
    if (r.fresnelF0 >= 0.f) v.features |= kFeatureFresnel;
    if (r.roughness > 0.f) v.features |= kFeatureGlossy; // NaN: a mirror
    const bool glossy = (v.filter().features & kFeatureGlossy) != 0;
    if (glossy) prepareGlossy(g, ctx.stats); // made in sync, unless it turned rough since
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.filter().name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    glBindTextureUnit(1, g.composites.id());
    glBindTextureUnit(2, g.sky.id());
    prog.setUniform("uLevelLayers", 1);
    prog.setUniform("uSky", 2);
    prog.setUniform("uHasSky", g.sky.id() != 0 ? 1 : 0);
    prog.setUniform("uProbeCount", int(g.volumes.size()));
    prog.setUniform("uCandidateCount", int(candidates.size()));
    if (!candidates.empty())
        glProgramUniform1iv(prog.id(), prog.uniformLocation("uCandidates[0]"),
                            GLsizei(candidates.size()), candidates.data());
    g.params.bind(glsl::kLevelParamsBinding);
    prog.setUniform("uF0", r.fresnelF0);
    if (glossy) {
        glBindTextureUnit(3, g.chainTexture.id());
        prog.setUniform("uLevelChain", 3);
        prog.setUniform("uChainSlots", chainArraySlots(*g.chains.front()));
        prog.setUniform("uRoughness", r.roughness);
        prog.setUniform("uChainLevels", int(g.chains.front()->levels.size()));
        glBindTextureUnit(4, ggxAlbedo_.id());
        prog.setUniform("uGgxAlbedo", 4);
        if (v.filter().roughnessMap) roughnessMaps_.bind(prog, r, ctx.stats);
    }
    ctx.scene.drawEntity(reflector, prog);
}

} // namespace specula
