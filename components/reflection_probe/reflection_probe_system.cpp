#include "reflection_probe_system.h"

#include "engine/core/error.h"
#include "engine/gpu/shader.h"

#include <algorithm>
#include <filesystem>

namespace specula {

struct ReflectionProbeSystem::ProbeGpu {
    ReflectionProbe component; // the copy the GPU state was built from
    std::shared_ptr<const DistanceProbeAsset> asset;
    DistanceLookupConfig config;
    gpu::Texture layers;
    gpu::Texture sky;
    std::size_t bytes = 0;
};

std::string featureName(std::uint32_t f) {
    std::string s;
    auto add = [&](std::uint32_t bit, const char* name) {
        if (!(f & bit)) return;
        if (!s.empty()) s += '+';
        s += name;
    };
    add(kFeatureLayers, "layers");
    add(kFeatureEnvmap, "envmap");
    add(kFeatureBoxProj, "boxproj");
    add(kFeatureBisection, "bisection");
    add(kFeatureSecant, "secant");
    add(kFeatureAvgDist, "avgdist");
    add(kFeatureFresnel, "fresnel");
    return s;
}

ReflectionProbeSystem::ReflectionProbeSystem() : timer_(std::make_unique<gpu::GpuTimer>()) {}
ReflectionProbeSystem::~ReflectionProbeSystem() = default;

gpu::Program& ReflectionProbeSystem::program(std::uint32_t f, int output) {
    const std::uint64_t key = std::uint64_t(f) | (std::uint64_t(output) << 32);
    auto it = programs_.find(key);
    if (it != programs_.end()) return it->second;
    auto bit = [&](std::uint32_t b) { return (f & b) ? "1" : "0"; };
    const std::vector<std::string> defines = {
        std::string("HAS_ENVMAP=") + bit(kFeatureEnvmap),
        std::string("HAS_BOXPROJ=") + bit(kFeatureBoxProj),
        std::string("HAS_BISECTION=") + bit(kFeatureBisection),
        std::string("HAS_SECANT=") + bit(kFeatureSecant),
        std::string("HAS_AVGDIST=") + bit(kFeatureAvgDist),
        std::string("HAS_LAYERS=") + bit(kFeatureLayers),
        std::string("HAS_FRESNEL=") + bit(kFeatureFresnel),
        "OUTPUT=" + std::to_string(output)};
    gpu::Program p = gpu::buildProgram(
        gpu::ShaderSource::file("components/reflection_probe/shaders/reflector.vert"),
        gpu::ShaderSource::file("components/reflection_probe/shaders/distance_reflector.frag"),
        defines);
    return programs_.emplace(key, std::move(p)).first->second;
}

void ReflectionProbeSystem::sync(ecs::Registry& registry) {
    // Drop probes whose entity or component is gone.
    std::erase_if(probes_, [&](const auto& kv) {
        return !registry.valid(kv.first) || !registry.has<ReflectionProbe>(kv.first);
    });
    registry.view<ReflectionProbe>().each([&](ecs::Entity e, ReflectionProbe& probe) {
        auto& slot = probes_[e];
        if (slot && slot->component == probe) return;
        if (probe.flavour != ProbeFlavour::DistanceCubemap)
            throw Error(probe.asset, "flavour", "this system draws distance-cubemap probes");

        auto gpuProbe = std::make_unique<ProbeGpu>();
        gpuProbe->component = probe;
        // Probes that share an asset share its CPU copy; the GPU copy is per probe since the
        // methods (and so the layers uploaded) may differ.
        auto& cached = assetCache_[probe.asset];
        gpuProbe->asset = cached.lock();
        if (!gpuProbe->asset) {
            gpuProbe->asset = std::make_shared<const DistanceProbeAsset>(readDistanceProbe(probe.asset));
            cached = gpuProbe->asset;
        }
        const DistanceProbeAsset& a = *gpuProbe->asset;
        gpuProbe->config = makeLookupConfig(probe, a);
        if (gpuProbe->config.layerMethods.size() > 64)
            throw Error(probe.asset, "layers", "at most 63 object layers are supported");

        // Only the layers the method reads go to the GPU: the composite alone unless layered.
        const int layerCount =
            (gpuProbe->config.features & kFeatureLayers) ? int(a.layers.size()) : 1;
        const int n = a.faceRes;
        gpuProbe->layers = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
        const GLuint tex = gpuProbe->layers.id();
        glTextureStorage3D(tex, 1, GL_RGBA32F, n, n, 6 * layerCount);
        for (int L = 0; L < layerCount; ++L)
            for (int f = 0; f < 6; ++f)
                glTextureSubImage3D(tex, 0, 0, 0, 6 * L + f, n, n, 1, GL_RGBA, GL_FLOAT,
                                    a.layers[std::size_t(L)].faces[std::size_t(f)].pixels.data());
        glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        gpuProbe->bytes = std::size_t(n) * n * 6 * layerCount * 16;

        if (!a.sky.empty()) {
            gpuProbe->sky = gpu::Texture::create(GL_TEXTURE_2D);
            const GLuint s = gpuProbe->sky.id();
            std::vector<float> rgba(std::size_t(a.sky.width) * a.sky.height * 4);
            for (int y = 0; y < a.sky.height; ++y)
                for (int x = 0; x < a.sky.width; ++x) {
                    const glm::vec4 v = a.sky.rgba(x, y);
                    std::copy(&v[0], &v[0] + 4, &rgba[(std::size_t(y) * a.sky.width + x) * 4]);
                }
            glTextureStorage2D(s, 1, GL_RGBA32F, a.sky.width, a.sky.height);
            glTextureSubImage2D(s, 0, 0, 0, a.sky.width, a.sky.height, GL_RGBA, GL_FLOAT,
                                rgba.data());
            glTextureParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
            glTextureParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            glTextureParameteri(s, GL_TEXTURE_WRAP_S, GL_REPEAT);
            glTextureParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            gpuProbe->bytes += rgba.size() * sizeof(float);
        }
        slot = std::move(gpuProbe);
    });
    stats_.probeGpuBytes = 0;
    for (const auto& [e, p] : probes_) stats_.probeGpuBytes += p->bytes;
}

void ReflectionProbeSystem::render(ecs::Registry& registry, const CameraView& camera,
                                   SceneRenderer& scene, gpu::RenderTarget& target, int output) {
    target.bind();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    stats_.reflectorsDrawn = 0;
    stats_.permutations.clear();
    timer_->begin();
    registry.view<Reflector>().each([&](ecs::Entity e, Reflector& r) {
        auto it = probes_.find(r.probe);
        if (it == probes_.end() || !scene.contains(e)) return;
        ProbeGpu& p = *it->second;
        const DistanceLookupConfig& c = p.config;
        std::uint32_t features = c.features;
        if (r.fresnelF0 >= 0.f) features |= kFeatureFresnel;
        gpu::Program& prog = program(features, output);
        const std::string name = featureName(features);
        if (std::find(stats_.permutations.begin(), stats_.permutations.end(), name) ==
            stats_.permutations.end())
            stats_.permutations.push_back(name);

        prog.use();
        SceneRenderer::setCameraUniforms(prog, camera);
        glBindTextureUnit(1, p.layers.id());
        glBindTextureUnit(2, p.sky.id());
        prog.setUniform("uLayers", 1);
        prog.setUniform("uSky", 2);
        prog.setUniform("uHasSky", p.sky.id() != 0 ? 1 : 0);
        prog.setUniform("uFaceRes", p.asset->faceRes);
        prog.setUniform("uProbeCentre", p.asset->centre);
        prog.setUniform("uBoxMin", c.boxMin);
        prog.setUniform("uBoxMax", c.boxMax);
        prog.setUniform("uRange", c.range);
        prog.setUniform("uTolerance", c.tolerance);
        prog.setUniform("uDInf", c.dInf);
        prog.setUniform("uMaxSteps", c.maxSteps);
        prog.setUniform("uMethod", c.method);
        prog.setUniform("uLayerCount", c.layerCount);
        prog.setUniform("uF0", r.fresnelF0);
        for (std::size_t i = 0; i < c.layerMethods.size(); ++i) {
            prog.setUniform("uLayerMethod[" + std::to_string(i) + "]", c.layerMethods[i]);
            prog.setUniform("uLayerAvgDistance[" + std::to_string(i) + "]",
                            c.layerAvgDistance[i]);
        }
        scene.drawEntity(e, prog);
        ++stats_.reflectorsDrawn;
    });
    timer_->end();
    stats_.reflectorPassMs = timer_->resultMs();
}

const DistanceProbeAsset* ReflectionProbeSystem::asset(ecs::Entity probe) const {
    auto it = probes_.find(probe);
    return it == probes_.end() ? nullptr : it->second->asset.get();
}

const DistanceLookupConfig* ReflectionProbeSystem::config(ecs::Entity probe) const {
    auto it = probes_.find(probe);
    return it == probes_.end() ? nullptr : &it->second->config;
}

} // namespace specula
