#pragma once
// A level of distance probes on the GPU (distance_level.h): every probe's composite in one
// texture array, their lookups and volumes in one uniform block, the sky, and (for rough
// reflectors) every probe's GGX chain in one array; and how a program that blends them
// (distance_level_reflector.frag, or a host's shader with distance_level_host.glsl) is bound
// to them. Specula's DistanceLevelStore (system/) and a host's DistanceLevelHostProbe both hold
// one. Needs a current GL 4.5 context.
#include "components/reflection_probe/distance/distance_level.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/level_index.h"
#include "components/reflection_probe/probe_volume.h"
#include "engine/core/glsl_host.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/texture_spec.h"
#include "engine/image/ggx_prefilter.h"
#include "engine/math/aabb.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace specula {
namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_level_params.glsl.h"
} // namespace glsl

// The most probes one level may hold on this GL context: the uniform block's
// kMaxLevelProbes, and GL_MAX_ARRAY_TEXTURE_LAYERS / 6.
int maxLevelProbes();

// The permutation defines of a level variant: the method's bit, HAS_GLOSSY, HAS_FRESNEL,
// COMPRESSED_COMPOSITE (features), HAS_ROUGHNESS_MAP, LEVEL_K and LEVEL_BLEND.
std::vector<std::string> distanceLevelDefines(std::uint32_t features, int k, LevelBlend blend,
                                              bool roughnessMap);

// Texture units and the uniform-buffer binding point the level's lookups read from.
struct DistanceLevelBindings {
    GLuint layers = 1, sky = 2, chains = 3, ggxAlbedo = 4, distances = 5;
    GLuint params = GLuint(glsl::kLevelParamsBinding); // the block's declared binding
};

// Reads one probe of the level (its manifest path): the store shares assets between levels.
using DistanceAssetReader =
    std::function<std::shared_ptr<const DistanceProbeAsset>(const std::string& manifestPath)>;

struct DistanceLevelGpu {
    std::string indexPath;
    std::vector<ProbeVolume> volumes; // blend order (probe_volume.h blendsBefore)
    std::vector<std::shared_ptr<const DistanceProbeAsset>> assets; // (the same order)
    gpu::Texture composites; // probe i's faces are layers 6i .. 6i+5
    // When every probe is compressed (DistanceCompression::Bc6h): `composites` holds their
    // radiance as BC6H and `distances` their distances (R16F when every probe's are halves,
    // else R32F), read by the COMPRESSED_COMPOSITE permutation. Otherwise RGBA32F composites.
    bool compressed = false, halfDistances = false;
    gpu::Texture distances;
    gpu::Texture sky;
    gpu::UniformBuffer<glsl::LevelParamsBlock> params;
    std::uint32_t methodFeature = 0; // the permutation bit of the settings' method
    // Every probe's composite GGX chain (glossyChainOf; blend order) and their levels 1.. in
    // one array (uploadChainArrays), once a rough reflector reads them (mutable: the store
    // makes them from hooks that get the level const).
    mutable std::vector<std::shared_ptr<const CubeChain>> chains;
    mutable gpu::Texture chainTexture;
    mutable bool chainsCompressed = false; // chainTexture is BC6H (every probe's glossyBlocks)
    // Where the textures come from (engine/gpu/texture_spec.h): the runtime's own, or the
    // host's in the unmanaged mode.
    gpu::TextureAllocator allocate = gpu::createTexture;

    // The index's probes in blend order, their composites and the sky uploaded. Throws Error
    // naming the index and field: another flavour, no probe, more than maxLevelProbes(),
    // probes of different face sizes.
    static DistanceLevelGpu load(const std::string& indexPath, const LevelIndex& index,
                                 const DistanceAssetReader& read,
                                 gpu::TextureAllocator allocate = gpu::createTexture);
    // The textures a level of `assets` allocates, with `chains` (makeChains) when a rough
    // reflector reads them: what a host makes for the unmanaged mode.
    static std::vector<gpu::TextureSpec>
    textureSpecs(const std::vector<std::shared_ptr<const DistanceProbeAsset>>& assets,
                 const std::vector<std::shared_ptr<const CubeChain>>* chains);
    // The block of `settings` (validateDistanceLevel first; throws before any change).
    void applySettings(const DistanceLevel& settings);
    // Every probe's chain, checked to be of one length (throws Error naming the probes).
    std::vector<std::shared_ptr<const CubeChain>> makeChains() const;
    // Uploads `made` (makeChains) unless the level has chains.
    void setChains(std::vector<std::shared_ptr<const CubeChain>> made) const;
    std::size_t gpuBytes() const;
    // The probes whose influence meets `bounds` (world space), in blend order: what each pixel
    // of a reflector inside them walks. Empty bounds: every probe.
    std::vector<GLint> candidatesFor(const Aabb& bounds) const;
    // Binds the textures and block on `b`'s units and binding point, points `program`'s
    // samplers and block at them and hands it the candidates. `glossy`: the chains and
    // `ggxAlbedo` too.
    void bindTo(GLuint program, const DistanceLevelBindings& b,
                const std::vector<GLint>& candidates, bool glossy,
                const gpu::Texture* ggxAlbedo) const;
};

} // namespace specula
