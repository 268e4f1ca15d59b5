#pragma once
// Distance probes' textures, written once for the single-probe store and the level store:
// cube layers as an RGBA32F texture array (six faces per cube, A = distance), the object
// layers as tiles (distance_layer_tiles.h) and the sky panorama. Need a current GL 4.5
// context.
//
// Every texture is allocated from a gpu::TextureSpec (the *Spec functions, named by the
// sampler uniform that reads it) through an allocator: the runtime's own (gpu::createTexture,
// the default) or a host's textures made from the same specs (gpu::hostTextureAllocator).
#include "components/reflection_probe/distance/distance_layer_tiles.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/texture_spec.h"
#include "engine/image/ggx_prefilter.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace specula {

// An array of `cubes` x 6 faces of faceRes^2 texels, bilinear, clamped at the face edges.
gpu::TextureSpec cubeArraySpec(int faceRes, int cubes); // "uLayers", RGBA32F
gpu::Texture createCubeArray(int faceRes, int cubes,
                             const gpu::TextureAllocator& allocate = gpu::createTexture);
// Writes `layer`'s six faces into array layers 6 cube .. 6 cube + 5.
void uploadCube(const gpu::Texture& array, int cube, const DistanceProbeLayer& layer);
std::size_t cubeArrayBytes(int faceRes, int cubes);
// A compressed composite (DistanceCompression::Bc6h): its radiance as a BC6H array
// (GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT) uploaded from the blocks as stored, and its distances
// as an R16F (`half`) or R32F array of the same layout, both bilinear and clamped.
gpu::TextureSpec compressedCubeArraySpec(int faceRes, int cubes); // "uLayers"
gpu::Texture createCompressedCubeArray(int faceRes, int cubes,
                                       const gpu::TextureAllocator& allocate = gpu::createTexture);
void uploadCompressedCube(const gpu::Texture& array, int cube,
                          const std::vector<std::uint8_t>& blocks);
gpu::TextureSpec distanceArraySpec(int faceRes, int cubes, bool half); // "uLayerDistance"
gpu::Texture createDistanceArray(int faceRes, int cubes, bool half,
                                 const gpu::TextureAllocator& allocate = gpu::createTexture);
void uploadDistance(const gpu::Texture& array, int cube, const DistanceProbeLayer& layer,
                    bool half);

// The object layers' tiles on the GPU (shaders/distance_probe_gpu.glsl, LAYER_TILES): the
// atlas as an RGBA32F or RGBA16F 2D array of `pages` layers, bilinear and clamped, and the
// table as an R32I 2D array (tilesPerFace^2, six layers per object layer) read by texelFetch.
// Both null when there are no object layers.
struct LayerTileTextures {
    gpu::Texture atlas, table;
};
// "uTileAtlas" and "uTileTable"; none without object layers.
std::vector<gpu::TextureSpec> layerTileSpecs(const LayerTiles& tiles);
LayerTileTextures uploadLayerTiles(const LayerTiles& tiles,
                                   const gpu::TextureAllocator& allocate = gpu::createTexture);
// What uploadLayerTiles allocates.
std::size_t layerTileBytes(const LayerTiles& tiles);

// The levels 1.. of a cube chain (engine/image/ggx_prefilter.h; level 0, the composite, is
// already in the cube array) as a mipmapped RGBA32F 2D array read by texelFetch
// (shaders/distance_glossy_gpu.glsl): level i at mip i - 1, array layers 0..5; levels past the
// mip pyramid (1 x 1 faces) in the last mip, six more layers each. Null for a chain of one
// level. Throws Error when level i's faces are not max(1, n >> i) square RGBA (n: level 0's).
gpu::Texture uploadChainArray(const CubeChain& chain);
// Several chains of the same shape (a level's probes) in one such array: chain c's level i at
// array layers 6 (c slots + s) + face, where slots = chainArraySlots (array layers of one
// chain / 6) and s the level's slot in its mip as above; chain 0 is laid out exactly as
// uploadChainArray lays out a single chain. Throws Error naming the chain when one differs in
// levels or face size from chain 0. Its bytes: chainArrayBytes(chain 0) x chains.
// With `blocks` (compressed probes, DistanceProbeAsset::glossyBlocks: blocks[c][k] chain c's
// level k + 1, six faces in order) the array is BC6H uploaded from them, its RGB what the
// shader reads; Error when they do not fit the chains' levels.
using ChainBlocks = std::vector<const std::vector<std::vector<std::uint8_t>>*>;
// Whether `chain` is `asset`'s own compressed levels (a Bc6h asset with glossyBlocks for each
// of them), so it goes up as those blocks; a chain prefiltered at load goes up as floats.
bool chainHasBlocks(const DistanceProbeAsset& asset, const CubeChain& chain);
gpu::Texture uploadChainArrays(const std::vector<const CubeChain*>& chains,
                               const ChainBlocks& blocks = {},
                               const gpu::TextureAllocator& allocate = gpu::createTexture);
// The array uploadChainArrays allocates for `chains` chains shaped as `chain` ("uChain").
gpu::TextureSpec chainArraySpec(const CubeChain& chain, int chains, bool bc6h);
int chainArraySlots(const CubeChain& chain);
// The array's bytes as uploaded: RGBA32F, or BC6H blocks (`bc6h`, uploadCompressedChainArray).
std::size_t chainArrayBytes(const CubeChain& chain, bool bc6h = false);

// The equirectangular sky, bilinear, repeating around the horizon.
gpu::TextureSpec skyTextureSpec(const Image& sky); // "uSky", RGBA32F
gpu::Texture uploadSkyTexture(const Image& sky,
                              const gpu::TextureAllocator& allocate = gpu::createTexture);
std::size_t skyTextureBytes(const Image& sky);

} // namespace specula
