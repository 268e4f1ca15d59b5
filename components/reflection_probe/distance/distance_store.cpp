#include "distance_store.h"

#include "engine/gpu/shader.h"

#include <algorithm>

namespace specula {

namespace {

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

DistanceVariant DistanceVariant::filter() const {
    DistanceVariant v = *this;
    if (v.output != 0) v.features &= ~kFeatureFresnel;
    return v;
}

gpu::Program DistanceVariant::build() const {
    auto bit = [&](std::uint32_t b) { return (features & b) ? "1" : "0"; };
    std::vector<std::string> defines;
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.define) defines.push_back(std::string(row.define) + "=" + bit(row.feature));
    defines.push_back(std::string("HAS_LAYERS=") + bit(kFeatureLayers));
    defines.push_back(std::string("HAS_FRESNEL=") + bit(kFeatureFresnel));
    defines.push_back("OUTPUT=" + std::to_string(output));
    return gpu::buildProgram(
        gpu::ShaderSource::file("components/reflection_probe/shaders/reflector.vert"),
        gpu::ShaderSource::file(
            "components/reflection_probe/distance/shaders/distance_reflector.frag"),
        defines);
}

DistanceProbeGpu DistanceStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats&) {
    DistanceProbeGpu g;
    g.asset = assets_.get(manifest.path, [&] { return readDistanceProbe(manifest); });
    if (!g.asset->sky.empty()) g.sky = uploadSky(*g.asset);
    return g;
}

void DistanceStore::applySettings(DistanceProbeGpu& g, const DistanceProbe& settings,
                                  ProbeFrameStats& stats) {
    const DistanceProbeAsset& a = *g.asset;
    DistanceLookupConfig config = makeLookupConfig(settings, a); // throws before any change
    // Only the layers the method reads go to the GPU: the composite alone unless layered. A
    // texture that already holds them is kept, so a method edit re-uploads only to grow.
    const int needed = (config.features & kFeatureLayers) ? int(a.layers.size()) : 1;
    if (needed > g.layersUploaded) {
        g.layers = uploadLayers(a, needed);
        g.layersUploaded = needed;
        ++stats.textureUploads;
    }
    g.config = std::move(config);
    g.params.upload(g.config);
    ++stats.parameterUploads;
}

std::size_t DistanceStore::gpuBytesOf(const DistanceProbeGpu& g) const {
    const DistanceProbeAsset& a = *g.asset;
    return layerTextureBytes(a, g.layersUploaded) + (a.sky.empty() ? 0 : skyTextureBytes(a));
}

void DistanceStore::drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                  const Reflector& r, const DistanceProbeGpu& p,
                                  const DistanceProbe&) {
    DistanceVariant v{p.config.features, ctx.output};
    if (r.fresnelF0 >= 0.f) v.features |= kFeatureFresnel;
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.filter().name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    glBindTextureUnit(1, p.layers.id());
    glBindTextureUnit(2, p.sky.id());
    prog.setUniform("uLayers", 1);
    prog.setUniform("uSky", 2);
    prog.setUniform("uHasSky", p.sky.id() != 0 ? 1 : 0);
    p.params.bind(glsl::kDistanceParamsBinding);
    prog.setUniform("uF0", r.fresnelF0);
    ctx.scene.drawEntity(reflector, prog);
}

const DistanceProbeAsset* DistanceStore::asset(ecs::Entity e) const {
    const DistanceProbeGpu* g = probe(e);
    return g ? g->asset.get() : nullptr;
}

const DistanceLookupConfig* DistanceStore::config(ecs::Entity e) const {
    const DistanceProbeGpu* g = probe(e);
    return g ? &g->config : nullptr;
}

} // namespace specula
