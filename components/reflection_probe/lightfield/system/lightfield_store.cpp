#include "lightfield_store.h"

#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/gpu/ggx_albedo_texture.h"
#include "engine/gpu/shader.h"
#include "engine/log/log.h"
#include "engine/scene/components.h"
#include "engine/scene/mesh_bounds.h"

#include <cmath>

namespace specula {

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

LightFieldGpuProbe LightFieldStore::loadProbe(const ProbeManifest& manifest,
                                              ProbeFrameStats& stats) {
    LightFieldGpuProbe g = LightFieldGpuProbe::load(
        assets_.get(manifest.path, [&] { return readLightFieldProbe(manifest); }), manifest.path);
    ++stats.textureUploads;
    return g;
}

std::size_t LightFieldStore::gpuBytesOf(const LightFieldGpuProbe& g) const {
    return g.gpuBytes();
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
        entry.probe.bindTo(prog.id(), {}, entry.settings, false, nullptr);
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
                                    const Reflector& r, const LightFieldGpuProbe& p,
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
    if (v.glossy) prepareGlossy(ctx, p); // may make the atlas again: before bindTo
    p.bindTo(prog.id(), {}, s, v.glossy, &ggxAlbedo_);
    if (v.glossy) {
        prog.setUniform("uRoughness", r.roughness);
        if (usesRoughnessMap(r)) roughnessMaps_.bind(prog, r, ctx.stats);
    }
    prog.setUniform("uF0", r.fresnelF0);
    ctx.scene.drawEntity(reflector, prog);
}

void LightFieldStore::prepareGlossy(const ProbeDrawContext& ctx, const LightFieldGpuProbe& p) {
    if (p.ensureMips()) ++ctx.stats.textureUploads;
    if (!ggxAlbedo_) {
        ggxAlbedo_ = gpu::createGgxAlbedoTexture();
        ++ctx.stats.textureUploads;
    }
}

void LightFieldStore::checkCell(const ProbeDrawContext& ctx, ecs::Entity reflector,
                                const LightFieldGpuProbe& p) {
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
    const LightFieldGpuProbe* g = probe(e);
    return g ? g->asset.get() : nullptr;
}

std::array<float, 6> LightFieldStore::disparities(ecs::Entity e) const {
    const LightFieldGpuProbe* g = probe(e);
    const LightFieldProbe* s = settings(e);
    if (!g || !s) return {};
    return effectiveDisparities(*g->asset, s->disparity);
}

} // namespace specula
