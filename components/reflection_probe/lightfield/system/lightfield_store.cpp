#include "lightfield_store.h"

#include "components/reflection_probe/lightfield/lightfield_mips.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"
#include "engine/log/log.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"

#include <cmath>

namespace specula {

namespace {

// The six slabs as one sRGB array layer each (the texels are sRGB codes, decoded to linear
// before filtering), with `mips` as levels 1.. when given. Throws Error naming the manifest
// when this GPU cannot hold it.
gpu::Texture uploadAtlas(const LightFieldAsset& a, const std::string& manifest,
                         const LightFieldMips* mips = nullptr) {
    GLint maxLayers = 0, maxSize = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int n = a.atlasSize();
    if (n > maxSize || maxLayers < 6)
        throw Error(manifest, "cameras",
                    "atlas of " + std::to_string(n) + "^2 x 6 exceeds this GPU's limits (" +
                        std::to_string(maxSize) + "^2, " + std::to_string(maxLayers) + " layers)");
    const bool bc1 = a.compression == LightFieldCompression::BC1;
    if (bc1 && !epoxy_has_gl_extension("GL_EXT_texture_compression_s3tc"))
        throw Error(manifest, "compression",
                    "bc1 needs GL_EXT_texture_compression_s3tc, which this context lacks");
    gpu::Texture atlas = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint tex = atlas.id();
    const int levels = 1 + (mips ? mips->maxLevel() : 0);
    glTextureStorage3D(tex, levels, bc1 ? GL_COMPRESSED_SRGB_S3TC_DXT1_EXT : GL_SRGB8_ALPHA8, n, n,
                       6);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int level = 0; level < levels; ++level)
        for (int k = 0; k < 6; ++k) {
            const auto& data = level == 0 ? a.slabs[std::size_t(k)].data
                                          : mips->levels[std::size_t(level - 1)][std::size_t(k)];
            const int m = n >> level;
            if (bc1)
                glCompressedTextureSubImage3D(tex, level, 0, 0, k, m, m, 1,
                                              GL_COMPRESSED_SRGB_S3TC_DXT1_EXT,
                                              GLsizei(data.size()), data.data());
            else
                glTextureSubImage3D(tex, level, 0, 0, k, m, m, 1, GL_RGB, GL_UNSIGNED_BYTE,
                                    data.data());
        }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // With mips: an integral lod reads exactly that level, bilinearly (the glossy lookup blends
    // two levels itself); lod 0 is level 0 as without them.
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                        levels > 1 ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (const GLenum err = glGetError(); err != GL_NO_ERROR)
        throw Error(manifest, "",
                    "uploading the light-field atlas failed (GL error " + std::to_string(err) +
                        ")");
    return atlas;
}

} // namespace

LightFieldVariant LightFieldVariant::filter() const {
    LightFieldVariant v = *this;
    if (v.background || v.output != 0) v.fresnel = v.glossy = false;
    if (!v.glossy) v.roughnessMap = false;
    return v;
}

std::string LightFieldVariant::name() const {
    std::string s = kLightFieldMethod.name;
    if (background) s += "+background";
    if (glossy) s += "+glossy";
    if (roughnessMap) s += "+roughness-map";
    if (fresnel) s += "+fresnel";
    return s;
}

gpu::Program LightFieldVariant::build() const {
    return gpu::buildProgram(
        gpu::ShaderSource::file(background ? "components/reflection_probe/shaders/fullscreen.vert"
                                           : "components/reflection_probe/shaders/reflector.vert"),
        gpu::ShaderSource::file(
            "components/reflection_probe/lightfield/shaders/lightfield_reflector.frag"),
        {std::string("HAS_FRESNEL=") + (fresnel ? "1" : "0"),
         std::string("BACKGROUND=") + (background ? "1" : "0"),
         std::string("GLOSSY=") + (glossy ? "1" : "0"),
         std::string("HAS_ROUGHNESS_MAP=") + (roughnessMap ? "1" : "0"),
         "OUTPUT=" + std::to_string(output)});
}

LightFieldProbeGpu LightFieldStore::loadProbe(const ProbeManifest& manifest,
                                              ProbeFrameStats& stats) {
    LightFieldProbeGpu g;
    g.manifestPath = manifest.path;
    g.asset = assets_.get(manifest.path, [&] { return readLightFieldProbe(manifest); });
    g.atlas = uploadAtlas(*g.asset, manifest.path);
    ++stats.textureUploads;
    return g;
}

std::size_t LightFieldStore::gpuBytesOf(const LightFieldProbeGpu& g) const {
    return g.asset->gpuBytes() + g.mipBytes;
}

void LightFieldStore::bind(gpu::Program& prog, const LightFieldProbeGpu& p,
                           const LightFieldProbe& s) const {
    const LightFieldAsset& a = *p.asset;
    glBindTextureUnit(1, p.atlas.id());
    prog.setUniform("uAtlas", 1);
    prog.setUniform("uAtlasSize", float(a.atlasSize()));
    prog.setUniform("uCellCentre", a.cellCentre);
    prog.setUniform("uHalfCell", a.halfCell());
    prog.setUniform("uCameras", a.cameras);
    prog.setUniform("uRes", a.res);
    const std::array<float, 6> d = effectiveDisparities(a, s.disparity);
    glProgramUniform1fv(prog.id(), prog.uniformLocation("uDisparity"), 6, d.data());
}

void LightFieldStore::drawBackground(const ProbeDrawContext& ctx) {
    for (const auto& [e, entry] : entries()) {
        if (!entry.applied || !entry.settings.background) continue;
        const LightFieldAsset& a = *entry.probe.asset;
        const glm::vec3 eye = ctx.camera.eye() - a.cellCentre;
        const float h = a.halfCell();
        if (!(std::abs(eye.x) <= h && std::abs(eye.y) <= h && std::abs(eye.z) <= h)) continue;
        if (!emptyVao_) emptyVao_ = gpu::VertexArray::create();
        const LightFieldVariant v{false, true, false, ctx.output};
        gpu::Program& prog = variants_.get(v);
        prog.use();
        SceneRenderer::setCameraUniforms(prog, ctx.camera);
        bind(prog, entry.probe, entry.settings);
        prog.setUniform("uInvViewProj", glm::inverse(ctx.camera.viewProj()));
        prog.setUniform("uViewport", glm::vec2(float(ctx.camera.width), float(ctx.camera.height)));
        GLboolean depthTest = GL_FALSE;
        glGetBooleanv(GL_DEPTH_TEST, &depthTest);
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        glBindVertexArray(emptyVao_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDepthMask(GL_TRUE);
        if (depthTest) glEnable(GL_DEPTH_TEST);
        ctx.stats.backgroundDrawn = true;
    }
}

void LightFieldStore::drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                    const Reflector& r, const LightFieldProbeGpu& p,
                                    const LightFieldProbe& s) {
    checkCell(ctx, reflector, p);
    // A rough reflector compiles the glossy lookup in (NaN roughness: a mirror); a scene of
    // mirrors never builds it, nor the mips.
    const LightFieldVariant v = LightFieldVariant{r.fresnelF0 >= 0.f, false, r.roughness > 0.f,
                                                  ctx.output, usesRoughnessMap(r)}
                                    .filter();
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    if (v.glossy) bindGlossy(ctx, prog, r, p); // may make the atlas again: before bind()
    bind(prog, p, s);
    prog.setUniform("uF0", r.fresnelF0);
    ctx.scene.drawEntity(reflector, prog);
}

void LightFieldStore::bindGlossy(const ProbeDrawContext& ctx, gpu::Program& prog,
                                 const Reflector& r, const LightFieldProbeGpu& p) {
    const LightFieldAsset& a = *p.asset;
    if (p.mipLevels == 0 && lightFieldMaxLevel(a.res, a.compression) > 0) {
        const LightFieldMips mips = buildLightFieldMips(a);
        p.atlas = uploadAtlas(a, p.manifestPath, &mips);
        p.mipLevels = mips.maxLevel();
        p.mipBytes = mips.gpuBytes(a.atlasSize(), a.compression);
        ++ctx.stats.textureUploads;
    }
    if (!ggxAlbedo_) {
        ggxAlbedo_ = gpu::createGgxAlbedoTexture();
        ++ctx.stats.textureUploads;
    }
    glBindTextureUnit(2, ggxAlbedo_.id());
    prog.setUniform("uGgxAlbedo", 2);
    prog.setUniform("uRoughness", r.roughness);
    prog.setUniform("uGlossyRays", kLightFieldGlossyRays);
    prog.setUniform("uRaysPerTexel", kLightFieldGlossyRaysPerTexel);
    prog.setUniform("uLevelBias", kLightFieldGlossyLevelBias);
    prog.setUniform("uMaxLevel", p.mipLevels);
    if (usesRoughnessMap(r)) roughnessMaps_.bind(prog, r, ctx.stats);
}

void LightFieldStore::checkCell(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                const LightFieldProbeGpu& p) {
    // Per frame, so from the 8 corners of the meshes' local bounds rather than every vertex.
    // Conservative: a rotated reflector's box is wider than its geometry, so one near a
    // cell face may be reported a little early, never one outside missed.
    const LightFieldAsset& a = *p.asset;
    const float over = meshWorldBoundsConservative(ctx.registry, reflector)
                           .overhang(Aabb::cube(a.cellCentre, a.halfCell()));
    if (!(over > 0.f)) return;
    ++ctx.stats.reflectorsOutsideCell;
    ctx.stats.reflectorLeftCell = true;
    if (warnedOutside_.insert(reflector).second) {
        const Name* name = ctx.registry.find<Name>(reflector);
        log().warn("reflector '{}' reaches {:.3f} m outside the light-field cell of {} (the "
                   "light field is exact only inside it)",
                   name ? name->value : "?", over, p.manifestPath);
    }
}

const LightFieldAsset* LightFieldStore::asset(ecs::Entity e) const {
    const LightFieldProbeGpu* g = probe(e);
    return g ? g->asset.get() : nullptr;
}

std::array<float, 6> LightFieldStore::disparities(ecs::Entity e) const {
    const LightFieldProbeGpu* g = probe(e);
    const LightFieldProbe* s = settings(e);
    if (!g || !s) return {};
    return effectiveDisparities(*g->asset, s->disparity);
}

} // namespace specula
