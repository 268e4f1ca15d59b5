#include "reflection_probe_system.h"

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/gpu/shader.h"

#include "components/reflection_probe/lightfield_probe_cpu.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace specula {

struct ReflectionProbeSystem::ProbeGpu {
    ReflectionProbe component; // the copy the GPU state was built from
    std::shared_ptr<const DistanceProbeAsset> asset;
    DistanceLookupConfig config;
    gpu::UniformBuffer<glsl::DistanceParamsBlock> params; // config's block, as the shader reads it
    gpu::Texture layers;
    int layersUploaded = 0; // cube layers in `layers`: the composite, or every layer
    gpu::Texture sky;
    std::size_t bytes = 0;
    // Light-field flavour: the cooked slabs and their atlas array (lightfield_asset.h).
    std::shared_ptr<const LightFieldAsset> lightField;
    gpu::Texture atlas;
};

namespace {
// Same flavour and asset: an edit of the other fields changes parameters only, which the
// uniforms and the parameter block carry; the textures stay.
bool sameAsset(const ReflectionProbe& a, const ReflectionProbe& b) {
    return a.flavour == b.flavour && a.asset == b.asset;
}

void refuseLightFieldMethod(const ReflectionProbe& probe) {
    if (probe.method == LookupMethod::LightField)
        throw Error(probe.asset, "method", "'lightfield' needs a probe of flavour LightFieldSlab");
}

std::size_t layerTextureBytes(const DistanceProbeAsset& a, int layerCount) {
    return std::size_t(a.faceRes) * std::size_t(a.faceRes) * 6 * std::size_t(layerCount) * 16;
}

std::size_t skyTextureBytes(const DistanceProbeAsset& a) {
    return std::size_t(a.sky.width) * std::size_t(a.sky.height) * 4 * sizeof(float);
}

// Layers 0 .. layerCount-1 of the asset as one RGBA32F array, six faces per layer.
gpu::Texture uploadLayers(const DistanceProbeAsset& a, int layerCount) {
    const int n = a.faceRes;
    gpu::Texture layers = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint tex = layers.id();
    glTextureStorage3D(tex, 1, GL_RGBA32F, n, n, 6 * layerCount);
    for (int L = 0; L < layerCount; ++L)
        for (int f = 0; f < 6; ++f)
            glTextureSubImage3D(tex, 0, 0, 0, 6 * L + f, n, n, 1, GL_RGBA, GL_FLOAT,
                                a.layers[std::size_t(L)].faces[std::size_t(f)].pixels.data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return layers;
}

gpu::Texture uploadSky(const DistanceProbeAsset& a) {
    gpu::Texture sky = gpu::Texture::create(GL_TEXTURE_2D);
    const GLuint s = sky.id();
    std::vector<float> rgba(std::size_t(a.sky.width) * a.sky.height * 4);
    for (int y = 0; y < a.sky.height; ++y)
        for (int x = 0; x < a.sky.width; ++x) {
            const glm::vec4 v = a.sky.rgba(x, y);
            std::copy(&v[0], &v[0] + 4, &rgba[(std::size_t(y) * a.sky.width + x) * 4]);
        }
    glTextureStorage2D(s, 1, GL_RGBA32F, a.sky.width, a.sky.height);
    glTextureSubImage2D(s, 0, 0, 0, a.sky.width, a.sky.height, GL_RGBA, GL_FLOAT, rgba.data());
    glTextureParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return sky;
}
} // namespace

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
    add(kFeatureLightField, "lightfield");
    add(kFeatureLightFieldBackground, "background");
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
    if (f & kFeatureLightField) {
        const bool background = (f & kFeatureLightFieldBackground) != 0;
        gpu::Program p = gpu::buildProgram(
            gpu::ShaderSource::file(background
                                        ? "components/reflection_probe/shaders/fullscreen.vert"
                                        : "components/reflection_probe/shaders/reflector.vert"),
            gpu::ShaderSource::file(
                "components/reflection_probe/shaders/lightfield_reflector.frag"),
            {std::string("HAS_FRESNEL=") + bit(kFeatureFresnel),
             std::string("BACKGROUND=") + bit(kFeatureLightFieldBackground),
             "OUTPUT=" + std::to_string(output)});
        return programs_.emplace(key, std::move(p)).first->second;
    }
    const std::vector<std::string> defines = {std::string("HAS_ENVMAP=") + bit(kFeatureEnvmap),
                                              std::string("HAS_BOXPROJ=") + bit(kFeatureBoxProj),
                                              std::string("HAS_BISECTION=") +
                                                  bit(kFeatureBisection),
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
        if (slot && sameAsset(slot->component, probe)) {
            if (probe.flavour == ProbeFlavour::LightFieldSlab)
                slot->component = probe; // disparity, background: uniforms at draw time
            else
                setDistanceParams(*slot, probe);
            return;
        }
        auto gpuProbe = std::make_unique<ProbeGpu>();
        gpuProbe->component = probe;
        if (probe.flavour == ProbeFlavour::LightFieldSlab) {
            syncLightField(*gpuProbe);
            ++stats_.textureUploads;
            slot = std::move(gpuProbe);
            return;
        }
        refuseLightFieldMethod(probe); // before reading the asset from disk
        // Probes that share an asset share its CPU copy; the GPU copy is per probe since the
        // methods (and so the layers uploaded) may differ.
        auto& cached = assetCache_[probe.asset];
        gpuProbe->asset = cached.lock();
        if (!gpuProbe->asset) {
            gpuProbe->asset =
                std::make_shared<const DistanceProbeAsset>(readDistanceProbe(probe.asset));
            cached = gpuProbe->asset;
        }
        setDistanceParams(*gpuProbe, probe); // throws on a bad configuration before uploading
        if (!gpuProbe->asset->sky.empty()) gpuProbe->sky = uploadSky(*gpuProbe->asset);
        slot = std::move(gpuProbe);
    });
    stats_.probeGpuBytes = 0;
    for (const auto& [e, p] : probes_)
        stats_.probeGpuBytes += p->bytes;
}

void ReflectionProbeSystem::setDistanceParams(ProbeGpu& g, const ReflectionProbe& probe) {
    refuseLightFieldMethod(probe); // an edit may set it too
    const DistanceProbeAsset& a = *g.asset;
    DistanceLookupConfig config = makeLookupConfig(probe, a); // throws before any change
    // Only the layers the method reads go to the GPU: the composite alone unless layered. A
    // texture that already holds them is kept, so a method edit re-uploads only to grow.
    const int needed = (config.features & kFeatureLayers) ? int(a.layers.size()) : 1;
    if (needed > g.layersUploaded) {
        g.layers = uploadLayers(a, needed);
        g.layersUploaded = needed;
        ++stats_.textureUploads;
    }
    g.bytes = layerTextureBytes(a, g.layersUploaded) + (a.sky.empty() ? 0 : skyTextureBytes(a));
    g.component = probe;
    g.config = std::move(config);
    g.params.upload(g.config);
    ++stats_.parameterUploads;
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
    stats_.reflectorsOutsideCell = 0;
    stats_.reflectorLeftCell = false;
    stats_.lightFieldBackgroundDrawn = false;
    // The light-field background replaces the environment's colour (its depth stays, so
    // reflectors are still occluded by it) before the timed reflector pass.
    for (const auto& [e, p] : probes_)
        if (p->lightField && p->component.lightFieldBackground) {
            const glm::vec3 eye = camera.eye() - p->lightField->cellCentre;
            const float h = p->lightField->halfCell();
            if (std::abs(eye.x) <= h && std::abs(eye.y) <= h && std::abs(eye.z) <= h) {
                drawLightFieldBackground(*p, camera, output);
                stats_.lightFieldBackgroundDrawn = true;
            }
        }
    timer_->begin();
    registry.view<Reflector>().each([&](ecs::Entity e, Reflector& r) {
        auto it = probes_.find(r.probe);
        if (it == probes_.end() || !scene.contains(e)) return;
        ProbeGpu& p = *it->second;
        if (p.lightField) {
            checkCell(registry, e, p);
            std::uint32_t features = kFeatureLightField;
            if (r.fresnelF0 >= 0.f) features |= kFeatureFresnel;
            gpu::Program& prog = program(features, output);
            const std::string name = featureName(features);
            if (std::find(stats_.permutations.begin(), stats_.permutations.end(), name) ==
                stats_.permutations.end())
                stats_.permutations.push_back(name);
            prog.use();
            SceneRenderer::setCameraUniforms(prog, camera);
            bindLightField(prog, p);
            prog.setUniform("uF0", r.fresnelF0);
            scene.drawEntity(e, prog);
            ++stats_.reflectorsDrawn;
            return;
        }
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
        p.params.bind(glsl::kDistanceParamsBinding);
        prog.setUniform("uF0", r.fresnelF0);
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

namespace specula {

void ReflectionProbeSystem::syncLightField(ProbeGpu& g) {
    const ReflectionProbe& probe = g.component;
    auto& cached = lightFieldCache_[probe.asset];
    g.lightField = cached.lock();
    if (!g.lightField) {
        g.lightField = std::make_shared<const LightFieldAsset>(readLightFieldProbe(probe.asset));
        cached = g.lightField;
    }
    const LightFieldAsset& a = *g.lightField;
    GLint maxLayers = 0, maxSize = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int n = a.atlasSize();
    if (n > maxSize || maxLayers < 6)
        throw Error(probe.asset, "cameras",
                    "atlas of " + std::to_string(n) + "^2 x 6 exceeds this GPU's limits (" +
                        std::to_string(maxSize) + "^2, " + std::to_string(maxLayers) + " layers)");
    const bool bc1 = a.compression == LightFieldCompression::BC1;
    if (bc1 && !epoxy_has_gl_extension("GL_EXT_texture_compression_s3tc"))
        throw Error(probe.asset, "compression",
                    "bc1 needs GL_EXT_texture_compression_s3tc, which this context lacks");
    g.atlas = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint tex = g.atlas.id();
    // sRGB formats: the texels are sRGB codes, decoded to linear before filtering.
    glTextureStorage3D(tex, 1, bc1 ? GL_COMPRESSED_SRGB_S3TC_DXT1_EXT : GL_SRGB8_ALPHA8, n, n, 6);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int k = 0; k < 6; ++k) {
        const auto& data = a.slabs[std::size_t(k)].data;
        if (bc1)
            glCompressedTextureSubImage3D(tex, 0, 0, 0, k, n, n, 1,
                                          GL_COMPRESSED_SRGB_S3TC_DXT1_EXT, GLsizei(data.size()),
                                          data.data());
        else
            glTextureSubImage3D(tex, 0, 0, 0, k, n, n, 1, GL_RGB, GL_UNSIGNED_BYTE, data.data());
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (const GLenum err = glGetError(); err != GL_NO_ERROR)
        throw Error(probe.asset, "",
                    "uploading the light-field atlas failed (GL error " + std::to_string(err) +
                        ")");
    g.bytes = a.gpuBytes();
}

void ReflectionProbeSystem::bindLightField(gpu::Program& prog, const ProbeGpu& p) {
    const LightFieldAsset& a = *p.lightField;
    glBindTextureUnit(1, p.atlas.id());
    prog.setUniform("uAtlas", 1);
    prog.setUniform("uAtlasSize", float(a.atlasSize()));
    prog.setUniform("uCellCentre", a.cellCentre);
    prog.setUniform("uHalfCell", a.halfCell());
    prog.setUniform("uCameras", a.cameras);
    prog.setUniform("uRes", a.res);
    const std::array<float, 6> d = effectiveDisparities(a, p.component.disparity);
    for (int k = 0; k < 6; ++k)
        prog.setUniform("uDisparity[" + std::to_string(k) + "]", d[std::size_t(k)]);
}

void ReflectionProbeSystem::drawLightFieldBackground(const ProbeGpu& p, const CameraView& camera,
                                                     int output) {
    if (!emptyVao_) emptyVao_ = gpu::VertexArray::create();
    gpu::Program& prog = program(kFeatureLightField | kFeatureLightFieldBackground, output);
    prog.use();
    SceneRenderer::setCameraUniforms(prog, camera);
    bindLightField(prog, p);
    prog.setUniform("uInvViewProj", glm::inverse(camera.viewProj()));
    prog.setUniform("uViewport", glm::vec2(float(camera.width), float(camera.height)));
    GLboolean depthTest = GL_FALSE;
    glGetBooleanv(GL_DEPTH_TEST, &depthTest);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glBindVertexArray(emptyVao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    if (depthTest) glEnable(GL_DEPTH_TEST);
}

void ReflectionProbeSystem::checkCell(ecs::Registry& registry, ecs::Entity reflector,
                                      const ProbeGpu& p) {
    // Per frame, so from the 8 corners of the meshes' local bounds rather than every vertex.
    // Conservative: a rotated reflector's box is wider than its geometry, so one near a
    // cell face may be reported a little early, never one outside missed.
    const LightFieldAsset& a = *p.lightField;
    const float over = meshWorldBoundsConservative(registry, reflector)
                           .overhang(Aabb::cube(a.cellCentre, a.halfCell()));
    if (!(over > 0.f)) return;
    ++stats_.reflectorsOutsideCell;
    stats_.reflectorLeftCell = true;
    if (warnedOutside_.insert(reflector).second) {
        const Name* name = registry.find<Name>(reflector);
        log().warn("reflector '{}' reaches {:.3f} m outside the light-field cell of {} (the "
                   "light field is exact only inside it)",
                   name ? name->value : "?", over, p.component.asset);
    }
}

const LightFieldAsset* ReflectionProbeSystem::lightFieldAsset(ecs::Entity probe) const {
    auto it = probes_.find(probe);
    return it == probes_.end() ? nullptr : it->second->lightField.get();
}

std::array<float, 6> ReflectionProbeSystem::lightFieldDisparities(ecs::Entity probe) const {
    auto it = probes_.find(probe);
    if (it == probes_.end() || !it->second->lightField) return {};
    return effectiveDisparities(*it->second->lightField, it->second->component.disparity);
}

} // namespace specula
