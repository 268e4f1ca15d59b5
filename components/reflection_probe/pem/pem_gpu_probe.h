#pragma once
// A parameterized-environment-map probe on the GPU: every sample map of the asset as one RGBA32F
// texture array (six layers per sample, every MIP level, NEAREST: the lookup filters itself; BC6H
// blocks as they are for a compressed asset, 1 byte a texel against 16), a
// distance-geometry asset's distance cube as six R32F layers, the local layer's maps when it has
// one, and the blend of the two samples nearest the parameter as one uniform block. A parameter
// edit rewrites the block only; the textures are uploaded once. Specula's own PemStore
// (system/) and a host's PemHostProbe both hold one. Needs a current GL 4.5 context.
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_probe.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h" // glsl::PemParams, pemParams
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/texture_spec.h"

#include <memory>

namespace specula {

// Texture units and the uniform-buffer binding point the lookup reads from.
struct PemBindings {
    GLuint maps = 1, distance = 2, local = 3;
    GLuint params = GLuint(glsl::kPemParamsBinding); // the block's declared binding
};

struct PemGpuProbe {
    std::shared_ptr<const PemAsset> asset;
    glsl::PemParams params{}; // what `block` holds
    gpu::UniformBuffer<glsl::PemParams> block;
    gpu::Texture maps;
    gpu::Texture distance; // the distance cube of distance-geometry assets, else empty
    gpu::Texture local;    // every sample's local layer (RGBA32F, layered as maps), or empty

    // Uploads the maps (and the distance cube; with `local` the local layer). Throws Error
    // naming the manifest when this GPU cannot hold them. `allocate`: where the textures come
    // from (texture_spec.h).
    static PemGpuProbe load(std::shared_ptr<const PemAsset> asset, bool local = true,
                            const gpu::TextureAllocator& allocate = gpu::createTexture);
    // The sample maps' array, "uPemMaps" (every MIP level), or the local layer's, "uPemLocal".
    static gpu::TextureSpec mapsSpec(const PemAsset& asset, bool local);
    static gpu::TextureSpec distanceSpec(const PemDistanceGeometry& g); // "uPemDistance"
    // The block of `settings` (pemParams: the two samples nearest the parameter, their weight).
    void applySettings(const PemProbe& settings);
    std::size_t gpuBytes() const;
    // Binds the maps (the distance cube; with `local` the local layer) and the block on `b`'s
    // units and binding point and points `program`'s samplers and block at them.
    void bindTo(GLuint program, const PemBindings& b, bool local) const;
};

// GPU bytes of the asset's distant maps as stored (every sample, every MIP level): RGBA32F
// 16 bytes a texel, BC6H 1 (the partial blocks of levels under 4^2 count whole).
std::size_t pemDistantMapBytes(const PemAsset& asset);

} // namespace specula
