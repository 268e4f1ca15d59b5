#pragma once
// A light-field-slab probe on the GPU: the six slab atlases as one sRGB texture array (its
// mips once a rough reflector reads them), and how a program that runs the lookup
// (lightfield_reflector.frag, or a host's shader with lightfield_host.glsl) is bound to it.
// Specula's own LightFieldStore (system/) and a host's LightFieldHostProbe both hold one, so the
// host path binds exactly what the sandbox draws with. Needs a current GL 4.5 context.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "components/reflection_probe/lightfield/lightfield_probe.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/texture_spec.h"

#include <array>
#include <memory>
#include <string>

namespace specula {

// Texture units the lookup reads from.
struct LightFieldBindings {
    GLuint atlas = 1, ggxAlbedo = 2;
};

struct LightFieldGpuProbe {
    std::string manifestPath;
    std::shared_ptr<const LightFieldAsset> asset;
    // The six slabs, level 0 only until the probe's first rough reflector draws; then made
    // again with the mips of lightfield_mips.h (mutable: Specula's store makes them from hooks
    // that get the probe const).
    mutable gpu::Texture atlas;
    mutable int mipLevels = 0;        // deepest mip level uploaded (0: none)
    mutable std::size_t mipBytes = 0; // their texture memory

    // Uploads level 0 (with `mips`, the mips too). Throws Error naming the manifest when this
    // GPU cannot hold the atlas (size, layers, BC1 without GL_EXT_texture_compression_s3tc).
    // `allocate`: where the atlas comes from (texture_spec.h).
    static LightFieldGpuProbe load(std::shared_ptr<const LightFieldAsset> asset,
                                   std::string manifestPath, bool mips = false,
                                   const gpu::TextureAllocator& allocate = gpu::createTexture);
    // The atlas "uAtlas" of `asset`, with its mips or level 0 alone.
    static gpu::TextureSpec atlasSpec(const LightFieldAsset& asset, bool mips);
    // Makes the atlas again with its mips unless it has them (or the asset has none to make).
    // True when it uploaded.
    bool ensureMips() const;
    std::size_t gpuBytes() const { return asset->gpuBytes() + mipBytes; }
    // Binds the atlas on `b.atlas` and sets `program`'s lookup uniforms, the slabs' disparities
    // from `settings` (its override, else the cooked ones). `glossy` (a GLOSSY program): the
    // glossy lookup's uniforms too, and `ggxAlbedo` on `b.ggxAlbedo`.
    void bindTo(GLuint program, const LightFieldBindings& b, const LightFieldProbe& settings,
                bool glossy, const gpu::Texture* ggxAlbedo) const;
};

} // namespace specula
