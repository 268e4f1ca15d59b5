#include "pem_gpu_probe.h"

#include "components/reflection_probe/host_probe.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "engine/core/error.h"
#include "engine/image/bc6h.h"

#include <vector>

namespace specula {

namespace {

std::size_t mapBytes(const PemAsset& a, bool withLocal) {
    const std::size_t distance =
        a.distance ? std::size_t(PemMap::texelCount(a.distance->faceRes)) * sizeof(float) : 0;
    const std::size_t local = withLocal ? std::size_t(PemMap::texelCount(a.localFaceRes)) *
                                              a.samples.size() * 4 * sizeof(float)
                                        : 0;
    return pemDistantMapBytes(a) + distance + local;
}

// Sample `s`'s distant map, level `level` (of side `size`), into array layers 6s .. 6s+5 of
// `tex`: a compressed asset's blocks as they are, else RGBA32F (alpha 1) through `rgba`.
void uploadMapLevel(GLuint tex, const PemAsset& a, std::size_t s, int level, int size,
                    std::vector<float>& rgba) {
    const PemSampleMap& sample = a.samples[s];
    if (a.compression == PemCompression::Bc6h) {
        const std::vector<std::uint8_t>& blocks = sample.blocks.at(std::size_t(level));
        glCompressedTextureSubImage3D(tex, level, 0, 0, 6 * int(s), size, size, 6,
                                      GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT, GLsizei(blocks.size()),
                                      blocks.data());
        return;
    }
    const PemMap& m = sample.map;
    const std::size_t offset = std::size_t(PemMap::levelOffset(a.faceRes, level));
    const std::size_t count = std::size_t(PemMap::texelCount(size));
    for (std::size_t t = 0; t < count; ++t)
        for (int c = 0; c < 4; ++c)
            rgba[t * 4 + std::size_t(c)] = c < 3 ? m.texels[offset + t][c] : 1.f;
    // Faces are contiguous blocks in cube order: one upload of six layers per level.
    glTextureSubImage3D(tex, level, 0, 0, 6 * int(s), size, size, 6, GL_RGBA, GL_FLOAT,
                        rgba.data());
}

// Every sample's six faces as array layers 6s .. 6s+5 of one RGBA32F array, the distant maps
// (alpha 1) or the local ones (premultiplied RGB, coverage). Throws Error naming the manifest
// when this GPU cannot hold that many layers.
gpu::Texture uploadMaps(const PemAsset& a, bool local, const gpu::TextureAllocator& allocate) {
    GLint maxLayers = 0, maxSize = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int n = local ? a.localFaceRes : a.faceRes, layers = 6 * int(a.samples.size());
    if (layers > maxLayers || n > maxSize)
        throw Error(a.manifestPath, "samples",
                    std::to_string(a.samples.size()) + " maps of " + std::to_string(n) +
                        "^2 x 6 exceed this GPU's limits (" + std::to_string(maxSize) + "^2, " +
                        std::to_string(maxLayers) + " layers)");
    const gpu::TextureSpec spec = PemGpuProbe::mapsSpec(a, local);
    gpu::Texture maps = allocate(spec);
    const GLuint tex = maps.id();
    const int levels = spec.levels;
    std::vector<float> rgba(std::size_t(PemMap::texelCount(n)) * 4);
    for (std::size_t s = 0; s < a.samples.size(); ++s) {
        if (!local) {
            for (int level = 0; level < levels; ++level)
                uploadMapLevel(tex, a, s, level, PemMap::levelRes(n, level), rgba);
            continue;
        }
        // The local layer: one level, premultiplied RGB and coverage.
        const PemMap& m = a.samples[s].local;
        for (std::size_t t = 0; t < m.alpha.size(); ++t) {
            for (int c = 0; c < 3; ++c)
                rgba[t * 4 + std::size_t(c)] = m.texels[t][c];
            rgba[t * 4 + 3] = m.alpha[t];
        }
        glTextureSubImage3D(tex, 0, 0, 0, 6 * int(s), n, n, 6, GL_RGBA, GL_FLOAT, rgba.data());
    }
    // The shader reads with texelFetch at levels and indices it picks and clamps itself
    // (pemFetchMap): no filtering, no wrapping. A mipmapped NEAREST minification filter with
    // every level present keeps the texture complete for texelFetch of any level.
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER,
                        levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, levels - 1);
    return maps;
}

// The distance cube as six R32F layers, once per probe. NEAREST: the lookup reads it with
// texelFetch at the nearest texel it computes itself (pem_distance_lookup.glsl.h).
gpu::Texture uploadDistance(const PemAsset& a, const gpu::TextureAllocator& allocate) {
    const PemDistanceGeometry& g = *a.distance;
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (g.faceRes > maxSize)
        throw Error(a.manifestPath, "distance.face_res",
                    "a distance cube of " + std::to_string(g.faceRes) +
                        "^2 exceeds this GPU's limit (" + std::to_string(maxSize) + "^2)");
    gpu::Texture tex = allocate(PemGpuProbe::distanceSpec(g));
    glTextureSubImage3D(tex.id(), 0, 0, 0, 0, g.faceRes, g.faceRes, 6, GL_RED, GL_FLOAT,
                        g.distances.data());
    glTextureParameteri(tex.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

} // namespace

gpu::TextureSpec PemGpuProbe::mapsSpec(const PemAsset& a, bool local) {
    // The distant maps' MIP levels are the texture's own levels (texelFetch reads level k);
    // the local layer has one.
    const int n = local ? a.localFaceRes : a.faceRes;
    // A compressed asset's distant maps are sampled from their BC6H blocks (texelFetch
    // decodes them); the local layer holds coverage alpha, which BC6H has not.
    const GLenum format = !local && a.compression == PemCompression::Bc6h
                              ? GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT
                              : GL_RGBA32F;
    return {local ? "uPemLocal" : "uPemMaps", GL_TEXTURE_2D_ARRAY,    format, n, n,
            6 * int(a.samples.size()),        local ? 1 : a.mipLevels};
}

gpu::TextureSpec PemGpuProbe::distanceSpec(const PemDistanceGeometry& g) {
    return {"uPemDistance", GL_TEXTURE_2D_ARRAY, GL_R32F, g.faceRes, g.faceRes, 6};
}

PemGpuProbe PemGpuProbe::load(std::shared_ptr<const PemAsset> asset, bool local,
                              const gpu::TextureAllocator& allocate) {
    PemGpuProbe g;
    g.asset = std::move(asset);
    g.maps = uploadMaps(*g.asset, false, allocate);
    if (local && g.asset->localLayer) g.local = uploadMaps(*g.asset, true, allocate);
    if (g.asset->distance) g.distance = uploadDistance(*g.asset, allocate);
    return g;
}

void PemGpuProbe::applySettings(const PemProbe& settings) {
    params = pemParams(*asset, settings);
    block.upload(params);
}

std::size_t PemGpuProbe::gpuBytes() const {
    return mapBytes(*asset, bool(local)) + sizeof(glsl::PemParams);
}

void PemGpuProbe::bindTo(GLuint program, const PemBindings& b, bool withLocal) const {
    bindSampler(program, "uPemMaps", b.maps, maps.id());
    if (distance) bindSampler(program, "uPemDistance", b.distance, distance.id());
    if (withLocal && local) bindSampler(program, "uPemLocal", b.local, local.id());
    block.bind(b.params);
    bindUniformBlock(program, "PemParamsUniforms", b.params);
}

std::size_t pemDistantMapBytes(const PemAsset& a) {
    std::size_t bytes = 0;
    for (int level = 0; level < a.mipLevels; ++level) {
        const int n = PemMap::levelRes(a.faceRes, level);
        bytes += a.compression == PemCompression::Bc6h
                     ? 6 * bc6hBytes(n, n)
                     : std::size_t(PemMap::texelCount(n)) * 4 * sizeof(float);
    }
    return bytes * a.samples.size();
}

} // namespace specula
