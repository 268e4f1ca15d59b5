#include "lightfield_gpu_probe.h"

#include "components/reflection_probe/host_probe.h"
#include "components/reflection_probe/lightfield/lightfield_mips.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/core/error.h"

namespace specula {

namespace {

// The six slabs as one sRGB array layer each (the texels are sRGB codes, decoded to linear
// before filtering), with `mips` as levels 1.. when given. Throws Error naming the manifest
// when this GPU cannot hold it.
gpu::Texture uploadAtlas(const LightFieldAsset& a, const std::string& manifest,
                         const LightFieldMips* mips = nullptr,
                         const gpu::TextureAllocator& allocate = gpu::createTexture) {
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
    gpu::Texture atlas = allocate(LightFieldGpuProbe::atlasSpec(a, mips != nullptr));
    const GLuint tex = atlas.id();
    const int levels = 1 + (mips ? mips->maxLevel() : 0);
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

void setFloat(GLuint program, const char* name, float v) {
    glProgramUniform1f(program, glGetUniformLocation(program, name), v);
}

} // namespace

gpu::TextureSpec LightFieldGpuProbe::atlasSpec(const LightFieldAsset& a, bool mips) {
    const bool bc1 = a.compression == LightFieldCompression::BC1;
    return {"uAtlas",
            GL_TEXTURE_2D_ARRAY,
            GLenum(bc1 ? GL_COMPRESSED_SRGB_S3TC_DXT1_EXT : GL_SRGB8_ALPHA8),
            a.atlasSize(),
            a.atlasSize(),
            6,
            1 + (mips ? lightFieldMaxLevel(a.res, a.compression) : 0)};
}

LightFieldGpuProbe LightFieldGpuProbe::load(std::shared_ptr<const LightFieldAsset> asset,
                                            std::string manifestPath, bool mips,
                                            const gpu::TextureAllocator& allocate) {
    LightFieldGpuProbe g;
    g.manifestPath = std::move(manifestPath);
    g.asset = std::move(asset);
    const LightFieldAsset& a = *g.asset;
    if (mips && lightFieldMaxLevel(a.res, a.compression) > 0) {
        const LightFieldMips m = buildLightFieldMips(a);
        g.atlas = uploadAtlas(a, g.manifestPath, &m, allocate);
        g.mipLevels = m.maxLevel();
        g.mipBytes = m.gpuBytes(a.atlasSize(), a.compression);
    } else {
        g.atlas = uploadAtlas(a, g.manifestPath, nullptr, allocate);
    }
    return g;
}

bool LightFieldGpuProbe::ensureMips() const {
    const LightFieldAsset& a = *asset;
    if (mipLevels > 0 || lightFieldMaxLevel(a.res, a.compression) == 0) return false;
    LightFieldGpuProbe withMips = load(asset, manifestPath, true);
    atlas = std::move(withMips.atlas);
    mipLevels = withMips.mipLevels;
    mipBytes = withMips.mipBytes;
    return true;
}

void LightFieldGpuProbe::bindTo(GLuint program, const LightFieldBindings& b,
                                const LightFieldProbe& settings, bool glossy,
                                const gpu::Texture* ggxAlbedo) const {
    const LightFieldAsset& a = *asset;
    bindSampler(program, "uAtlas", b.atlas, atlas.id());
    setFloat(program, "uAtlasSize", float(a.atlasSize()));
    glProgramUniform3f(program, glGetUniformLocation(program, "uCellCentre"), a.cellCentre.x,
                       a.cellCentre.y, a.cellCentre.z);
    setFloat(program, "uHalfCell", a.halfCell());
    setIntUniform(program, "uCameras", a.cameras);
    setIntUniform(program, "uRes", a.res);
    const std::array<float, 6> d = effectiveDisparities(a, settings.disparity);
    glProgramUniform1fv(program, glGetUniformLocation(program, "uDisparity"), 6, d.data());
    if (!glossy) return;
    if (ggxAlbedo) bindSampler(program, "uGgxAlbedo", b.ggxAlbedo, ggxAlbedo->id());
    setIntUniform(program, "uGlossyRays", kLightFieldGlossyRays);
    setFloat(program, "uRaysPerTexel", kLightFieldGlossyRaysPerTexel);
    setFloat(program, "uLevelBias", kLightFieldGlossyLevelBias);
    setIntUniform(program, "uMaxLevel", mipLevels);
}

} // namespace specula
