#include "distance_textures.h"

#include "engine/core/error.h"
#include "engine/image/bc6h.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

namespace specula {

namespace {

gpu::TextureSpec faceArraySpec(const char* name, GLenum format, int faceRes, int cubes) {
    return {name, GL_TEXTURE_2D_ARRAY, format, faceRes, faceRes, 6 * cubes};
}

// The array of `spec` (faceArraySpec), bilinear, clamped at the face edges.
gpu::Texture createFaceArray(const gpu::TextureSpec& spec, const gpu::TextureAllocator& allocate) {
    gpu::Texture array = allocate(spec);
    const GLuint tex = array.id();
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return array;
}

} // namespace

gpu::TextureSpec cubeArraySpec(int faceRes, int cubes) {
    return faceArraySpec("uLayers", GL_RGBA32F, faceRes, cubes);
}

gpu::Texture createCubeArray(int faceRes, int cubes, const gpu::TextureAllocator& allocate) {
    return createFaceArray(cubeArraySpec(faceRes, cubes), allocate);
}

gpu::TextureSpec compressedCubeArraySpec(int faceRes, int cubes) {
    return faceArraySpec("uLayers", GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT, faceRes, cubes);
}

gpu::Texture createCompressedCubeArray(int faceRes, int cubes,
                                       const gpu::TextureAllocator& allocate) {
    return createFaceArray(compressedCubeArraySpec(faceRes, cubes), allocate);
}

void uploadCompressedCube(const gpu::Texture& array, int cube,
                          const std::vector<std::uint8_t>& blocks) {
    GLint n = 0;
    glGetTextureLevelParameteriv(array.id(), 0, GL_TEXTURE_WIDTH, &n);
    const std::size_t faceBytes = bc6hBytes(n, n);
    if (blocks.size() != 6 * faceBytes)
        throw Error("", "blocks",
                    "a compressed cube of " + std::to_string(n) + " needs " +
                        std::to_string(6 * faceBytes) + " bytes, got " +
                        std::to_string(blocks.size()));
    glCompressedTextureSubImage3D(array.id(), 0, 0, 0, 6 * cube, n, n, 6,
                                  GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT, GLsizei(blocks.size()),
                                  blocks.data());
}

gpu::TextureSpec distanceArraySpec(int faceRes, int cubes, bool half) {
    return faceArraySpec("uLayerDistance", half ? GL_R16F : GL_R32F, faceRes, cubes);
}

gpu::Texture createDistanceArray(int faceRes, int cubes, bool half,
                                 const gpu::TextureAllocator& allocate) {
    return createFaceArray(distanceArraySpec(faceRes, cubes, half), allocate);
}

void uploadDistance(const gpu::Texture& array, int cube, const DistanceProbeLayer& layer,
                    bool half) {
    for (int f = 0; f < 6; ++f) {
        const Image& face = layer.faces[std::size_t(f)];
        const std::size_t texels = std::size_t(face.width) * std::size_t(face.height);
        // Converted here, not by the driver, as the half atlas is: the texture then holds
        // exactly the values the CPU twin reads.
        std::vector<float> d(texels);
        for (std::size_t t = 0; t < texels; ++t)
            d[t] = face.pixels[t * std::size_t(face.channels) + 3];
        if (half) {
            std::vector<std::uint16_t> bits(texels);
            for (std::size_t t = 0; t < texels; ++t)
                bits[t] = glm::packHalf1x16(d[t]);
            glTextureSubImage3D(array.id(), 0, 0, 0, 6 * cube + f, face.width, face.height, 1,
                                GL_RED, GL_HALF_FLOAT, bits.data());
        } else {
            glTextureSubImage3D(array.id(), 0, 0, 0, 6 * cube + f, face.width, face.height, 1,
                                GL_RED, GL_FLOAT, d.data());
        }
    }
}

void uploadCube(const gpu::Texture& array, int cube, const DistanceProbeLayer& layer) {
    for (int f = 0; f < 6; ++f) {
        const Image& face = layer.faces[std::size_t(f)];
        glTextureSubImage3D(array.id(), 0, 0, 0, 6 * cube + f, face.width, face.height, 1, GL_RGBA,
                            GL_FLOAT, face.pixels.data());
    }
}

std::size_t cubeArrayBytes(int faceRes, int cubes) {
    return std::size_t(faceRes) * std::size_t(faceRes) * 6 * std::size_t(cubes) * 16;
}

std::vector<gpu::TextureSpec> layerTileSpecs(const LayerTiles& t) {
    if (t.layers == 0) return {};
    return {{"uTileAtlas", GL_TEXTURE_2D_ARRAY, GLenum(t.half ? GL_RGBA16F : GL_RGBA32F), t.width(),
             t.height(), t.pages},
            {"uTileTable", GL_TEXTURE_2D_ARRAY, GL_RGBA16I, t.tilesPerFace, t.tilesPerFace,
             6 * t.layers}};
}

LayerTileTextures uploadLayerTiles(const LayerTiles& t, const gpu::TextureAllocator& allocate) {
    LayerTileTextures g;
    if (t.layers == 0) return g;
    const std::vector<gpu::TextureSpec> specs = layerTileSpecs(t);
    g.atlas = allocate(specs[0]);
    const GLuint a = g.atlas.id();
    if (t.half) {
        // Converted here, not by the driver: the atlas then holds exactly the values the
        // tiles (and the CPU twin, roundObjectLayersToHalf) hold, whatever the driver rounds.
        std::vector<std::uint16_t> bits(t.atlas.size());
        for (std::size_t i = 0; i < bits.size(); ++i)
            bits[i] = glm::packHalf1x16(t.atlas[i]);
        glTextureSubImage3D(a, 0, 0, 0, 0, t.width(), t.height(), t.pages, GL_RGBA, GL_HALF_FLOAT,
                            bits.data());
    } else {
        glTextureSubImage3D(a, 0, 0, 0, 0, t.width(), t.height(), t.pages, GL_RGBA, GL_FLOAT,
                            t.atlas.data());
    }
    glTextureParameteri(a, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(a, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(a, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(a, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);

    g.table = allocate(specs[1]);
    const GLuint tb = g.table.id();
    const std::vector<std::int16_t> origins = t.tableOrigins();
    glTextureSubImage3D(tb, 0, 0, 0, 0, t.tilesPerFace, t.tilesPerFace, 6 * t.layers,
                        GL_RGBA_INTEGER, GL_SHORT, origins.data());
    glTextureParameteri(tb, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tb, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return g;
}

std::size_t layerTileBytes(const LayerTiles& t) {
    return t.layers == 0 ? 0 : t.atlasBytes() + t.tableBytes();
}

namespace {

// Mips of the chain array: level 1's faces halved down to 1 x 1, at most one per level.
int chainMips(const CubeChain& chain) {
    const int levels = int(chain.levels.size()) - 1;
    int mips = 1;
    for (int n = chain.levels[1][0].width; n > 1 && mips < levels; n /= 2)
        ++mips;
    return mips;
}

// The array of chainArraySpec, read by texelFetch only: nearest filters keep it complete at
// every mip.
gpu::Texture createChainArray(const gpu::TextureSpec& spec, const gpu::TextureAllocator& allocate) {
    gpu::Texture array = allocate(spec);
    const GLuint tex = array.id();
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return array;
}

} // namespace

// Level 1's faces as mip 0, its mips, chainArraySlots slots of six layers per chain.
gpu::TextureSpec chainArraySpec(const CubeChain& chain, int chains, bool bc6h) {
    const int base = chain.levels[1][0].width, mips = chainMips(chain);
    const int slots = int(chain.levels.size()) - mips;
    return {"uChain",
            GL_TEXTURE_2D_ARRAY,
            GLenum(bc6h ? GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT : GL_RGBA32F),
            base,
            base,
            6 * slots * chains,
            mips};
}

gpu::Texture uploadChainArray(const CubeChain& chain) {
    return uploadChainArrays({&chain});
}

namespace {

// That every chain has chain 0's levels, each max(1, n >> i) square RGBA, and (when `blocks`
// are given) that chain c's level i has 6 faces of BC6H blocks of that size.
void checkChains(const std::vector<const CubeChain*>& chains, const ChainBlocks& blocks) {
    const CubeChain& first = *chains.front();
    // The shader computes level i's size from the composite's (chainFaceRes).
    const int n = first.levels[0][0].width;
    if (!blocks.empty() && blocks.size() != chains.size())
        throw Error("", "glossy blocks",
                    std::to_string(blocks.size()) + " chains of blocks for " +
                        std::to_string(chains.size()) + " chains");
    for (std::size_t c = 0; c < chains.size(); ++c) {
        const std::string chain = chains.size() > 1 ? "chain " + std::to_string(c) + " " : "";
        if (chains[c]->levels.size() != first.levels.size() || chains[c]->levels[0][0].width != n)
            throw Error("", chain + "levels",
                        "every chain of one array has chain 0's " +
                            std::to_string(first.levels.size()) + " levels of " +
                            std::to_string(n) + "^2 faces");
        if (!blocks.empty() && blocks[c]->size() != first.levels.size() - 1)
            throw Error("", chain + "glossy blocks",
                        std::to_string(blocks[c]->size()) + " levels of blocks for " +
                            std::to_string(first.levels.size() - 1) + " glossy levels");
        for (std::size_t i = 1; i < first.levels.size(); ++i) {
            const int want = std::max(1, n >> std::min(int(i), 30));
            const std::string level = chain + "glossy level " + std::to_string(i);
            for (int f = 0; f < 6; ++f) {
                const Image& face = chains[c]->levels[i][std::size_t(f)];
                if (face.width != want || face.height != want || face.channels != 4)
                    throw Error("", level + " face " + std::to_string(f),
                                "expected " + std::to_string(want) + "x" + std::to_string(want) +
                                    " RGBA, got " + std::to_string(face.width) + "x" +
                                    std::to_string(face.height) + " with " +
                                    std::to_string(face.channels) + " channels");
            }
            if (!blocks.empty() && (*blocks[c])[i - 1].size() != 6 * bc6hBytes(want, want))
                throw Error("", level,
                            "holds " + std::to_string((*blocks[c])[i - 1].size()) +
                                " bytes of blocks, " + std::to_string(6 * bc6hBytes(want, want)) +
                                " expected");
        }
    }
}

} // namespace

gpu::Texture uploadChainArrays(const std::vector<const CubeChain*>& chains,
                               const ChainBlocks& blocks, const gpu::TextureAllocator& allocate) {
    if (chains.empty() || chains.front()->levels.size() < 2) return {};
    checkChains(chains, blocks);
    const CubeChain& first = *chains.front();
    const int mips = chainMips(first);
    const int slots = int(first.levels.size()) - mips; // level i at slot i - 1 - mip
    const bool bc6h = !blocks.empty();
    gpu::Texture array =
        createChainArray(chainArraySpec(first, int(chains.size()), bc6h), allocate);
    const GLuint tex = array.id();
    for (std::size_t c = 0; c < chains.size(); ++c)
        for (std::size_t i = 1; i < first.levels.size(); ++i) {
            const int mip = std::min(int(i) - 1, mips - 1), slot = int(i) - 1 - mip;
            const int layer = 6 * (int(c) * slots + slot), w = first.levels[i][0].width;
            if (bc6h) { // the six faces' blocks in order: one upload of six layers
                const std::vector<std::uint8_t>& b = (*blocks[c])[i - 1];
                glCompressedTextureSubImage3D(tex, mip, 0, 0, layer, w, w, 6,
                                              GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT,
                                              GLsizei(b.size()), b.data());
                continue;
            }
            for (int f = 0; f < 6; ++f)
                glTextureSubImage3D(tex, mip, 0, 0, layer + f, w, w, 1, GL_RGBA, GL_FLOAT,
                                    chains[c]->levels[i][std::size_t(f)].pixels.data());
        }
    return array;
}

bool chainHasBlocks(const DistanceProbeAsset& asset, const CubeChain& chain) {
    return asset.compression == DistanceCompression::Bc6h && !asset.glossyBlocks.empty() &&
           chain.levels.size() == asset.glossyBlocks.size() + 1;
}

int chainArraySlots(const CubeChain& chain) {
    return chain.levels.size() < 2 ? 0 : int(chain.levels.size()) - chainMips(chain);
}

std::size_t chainArrayBytes(const CubeChain& chain, bool bc6h) {
    if (chain.levels.size() < 2) return 0;
    const int base = chain.levels[1][0].width, mips = chainMips(chain);
    const int slots = int(chain.levels.size()) - mips;
    std::size_t bytes = 0;
    for (int m = 0; m < mips; ++m) {
        const int n = std::max(1, base >> m);
        const std::size_t face = bc6h ? bc6hBytes(n, n) : std::size_t(n) * std::size_t(n) * 16;
        bytes += face * 6 * std::size_t(slots);
    }
    return bytes;
}

gpu::TextureSpec skyTextureSpec(const Image& sky) {
    return {"uSky", GL_TEXTURE_2D, GL_RGBA32F, sky.width, sky.height};
}

gpu::Texture uploadSkyTexture(const Image& sky, const gpu::TextureAllocator& allocate) {
    gpu::Texture texture = allocate(skyTextureSpec(sky));
    const GLuint s = texture.id();
    std::vector<float> rgba(std::size_t(sky.width) * sky.height * 4);
    for (int y = 0; y < sky.height; ++y)
        for (int x = 0; x < sky.width; ++x) {
            const glm::vec4 v = sky.rgba(x, y);
            std::copy(&v[0], &v[0] + 4, &rgba[(std::size_t(y) * sky.width + x) * 4]);
        }
    glTextureSubImage2D(s, 0, 0, 0, sky.width, sky.height, GL_RGBA, GL_FLOAT, rgba.data());
    glTextureParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(s, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

std::size_t skyTextureBytes(const Image& sky) {
    return std::size_t(sky.width) * std::size_t(sky.height) * 4 * sizeof(float);
}

} // namespace specula
