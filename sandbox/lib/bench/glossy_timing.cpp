#include "sandbox/lib/bench/glossy_timing.h"

#include "components/reflection_probe/distance/distance_textures.h"
#include "components/reflection_probe/distance/system/distance_store.h"
#include "components/reflection_probe/lightfield/lightfield_mips.h"
#include "components/reflection_probe/lightfield/lightfield_probe.h"
#include "components/reflection_probe/system/flavour_store_base.h"
#include "engine/gpu/timer.h"
#include "engine/image/ggx_albedo.h"
#include "sandbox/lib/render/frame_renderer.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <algorithm>
#include <array>
#include <optional>
#include <unordered_set>

namespace specula::sandbox {

namespace {

constexpr std::array<GlossyBenchMethod, 5> kGpuMethods{
    GlossyBenchMethod::EnvmapChain, GlossyBenchMethod::BoxprojChain,
    GlossyBenchMethod::RectifiedFootprint, GlossyBenchMethod::LayeredFootprint,
    GlossyBenchMethod::LightField};

} // namespace

DistanceProbe layeredSearch(const DistanceProbe& search) {
    DistanceProbe layered = search;
    layered.method = DistanceMethod::Layered;
    layered.layerMethod = search.method;
    return layered;
}

bool hasGpuPath(GlossyBenchMethod method) {
    return std::find(kGpuMethods.begin(), kGpuMethods.end(), method) != kGpuMethods.end();
}

std::size_t GlossyTextures::bytes(GlossyBenchMethod method, float roughness) const {
    const bool rough = roughness > 0.f;
    const std::size_t perReflector = rough ? albedoTable + roughnessMaps : 0;
    if (method == GlossyBenchMethod::LightField) return atlas + (rough ? mips : 0) + perReflector;
    return cube + sky + (method == GlossyBenchMethod::LayeredFootprint ? layers : 0) +
           (rough ? chain : 0) + perReflector;
}

GlossyTextures glossyTextures(const DistanceProbeAsset& distance, const CubeChain& chain,
                              const LightFieldAsset& lightField, const SceneMarkup& markup) {
    GlossyTextures t;
    std::unordered_set<const Image*> maps;
    for (const ReflectorMarkup& r : markup.reflectors)
        if (r.roughnessMap && maps.insert(r.roughnessMap.get()).second)
            t.roughnessMaps += roughnessMapTextureBytes(*r.roughnessMap);
    t.cube = cubeArrayBytes(distance.faceRes, 1);
    t.sky = distance.sky.empty() ? 0 : skyTextureBytes(distance.sky);
    t.chain = chainArrayBytes(chain);
    t.layers = layerTileBytes(storedLayerTiles(storedDistanceAsset(distance)));
    t.atlas = lightField.gpuBytes();
    if (lightFieldMaxLevel(lightField.res, lightField.compression) > 0)
        t.mips = buildLightFieldMips(lightField)
                     .gpuBytes(lightField.atlasSize(), lightField.compression);
    t.albedoTable = std::size_t(kGgxAlbedoTableSize) * kGgxAlbedoTableSize * sizeof(float);
    return t;
}

GlossyTiming timeGlossyPasses(ReflectionScene& rs, const std::string& distanceManifest,
                              const std::string& lightFieldManifest, const DistanceProbe& search,
                              const CameraView& camera, const std::vector<float>& roughness,
                              const GlossyTextures& textures, int rounds) {
    ecs::Registry& reg = rs.registry();
    // One probe entity per method on the same assets: the envmap one carries the reflectors.
    DistanceProbe envmap = search, boxproj = search;
    envmap.method = DistanceMethod::Envmap;
    boxproj.method = DistanceMethod::BoxProj;
    const ecs::Entity envmapProbe = rs.attachProbe(distanceManifest, envmap);
    const auto probeOn = [&](const std::string& manifest) {
        const ecs::Entity e = reg.create();
        reg.emplace<ReflectionProbe>(e, ReflectionProbe{manifest});
        return e;
    };
    const ecs::Entity boxprojProbe = probeOn(distanceManifest);
    reg.emplace<DistanceProbe>(boxprojProbe, boxproj);
    const ecs::Entity searchProbe = probeOn(distanceManifest);
    reg.emplace<DistanceProbe>(searchProbe, search);
    const ecs::Entity layeredProbe = probeOn(distanceManifest);
    reg.emplace<DistanceProbe>(layeredProbe, layeredSearch(search));
    const ecs::Entity lightFieldProbe = probeOn(lightFieldManifest);
    reg.emplace<LightFieldProbe>(lightFieldProbe, LightFieldProbe{});
    const auto probeOf = [&](GlossyBenchMethod m) {
        switch (m) {
        case GlossyBenchMethod::BoxprojChain:
            return boxprojProbe;
        case GlossyBenchMethod::RectifiedFootprint:
            return searchProbe;
        case GlossyBenchMethod::LayeredFootprint:
            return layeredProbe;
        case GlossyBenchMethod::LightField:
            return lightFieldProbe;
        default:
            return envmapProbe;
        }
    };

    struct Config {
        float roughness = 0.f;
        std::optional<GlossyBenchMethod> method; // none: the mirror envmap reference
        ecs::Entity probe;
        std::vector<double> samples;
    };
    std::vector<Config> configs{{0.f, std::nullopt, envmapProbe, {}}};
    for (const float r : roughness)
        for (const GlossyBenchMethod m : kGpuMethods)
            configs.push_back({r, m, probeOf(m), {}});

    GlossyTiming timing;
    {
        FrameRenderer fr(rs, camera.width, camera.height);
        timing.timer = fr.timerSource();
        // The configuration's roughness is each Reflector's factor: its roughnessMap (from the
        // markup, attachProbeComponents) stays, so the pass reads factor x map per pixel as
        // the bench's CPU rows do.
        const auto use = [&](const Config& c) {
            reg.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
                r.probe = c.probe;
                r.roughness = c.roughness;
            });
        };
        for (const Config& c : configs) { // warm-up: every variant compiled, every chain made
            use(c);
            fr.draw(camera);
        }
        for (int round = 0; round < rounds; ++round)
            for (Config& c : configs) {
                use(c);
                fr.draw(camera); // what a switch costs lands outside the timed frame
                fr.draw(camera);
                c.samples.push_back(fr.passMs());
            }
        timing.storeBytes = fr.stats().probeGpuBytes;
    }
    timing.envmapMs = gpu::medianMs(configs.front().samples);
    for (Config& c : configs) {
        if (!c.method) continue;
        GlossyPassTime t;
        t.roughness = c.roughness;
        t.method = *c.method;
        t.ms = gpu::medianMs(c.samples);
        t.frames = int(c.samples.size());
        t.ratioToEnvmap = timing.envmapMs > 0 ? t.ms / timing.envmapMs : 0.0;
        timing.passes.push_back(t);
    }
    // What the stores hold: four distance probes (composite and sky; with the chain once a
    // rough reflector drew), the layered one with the object layers' tiles, and the light
    // field (with its mips likewise); once a rough reflector drew, the distance store and the
    // light-field store each hold the roughness maps. The albedo tables are the stores' own,
    // outside their probes' count.
    const bool rough =
        std::any_of(roughness.begin(), roughness.end(), [](float r) { return r > 0.f; });
    timing.expectedStoreBytes = 4 * (textures.cube + textures.sky + (rough ? textures.chain : 0)) +
                                textures.layers + textures.atlas +
                                (rough ? textures.mips + 2 * textures.roughnessMaps : 0);
    reg.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
        r.probe = envmapProbe;
        r.roughness = 0.f;
    });
    for (const ecs::Entity e : {boxprojProbe, searchProbe, layeredProbe, lightFieldProbe})
        reg.destroy(e);
    return timing;
}

} // namespace specula::sandbox
