#include "pem_store.h"

#include "engine/core/error.h"
#include "engine/gpu/shader.h"

#include <vector>

namespace specula {

namespace {

std::size_t mapBytes(const PemAsset& a) {
    const std::size_t distance =
        a.distance ? std::size_t(PemMap::texelCount(a.distance->faceRes)) * sizeof(float) : 0;
    const std::size_t local = a.localLayer ? std::size_t(PemMap::texelCount(a.localFaceRes)) *
                                                 a.samples.size() * 4 * sizeof(float)
                                           : 0;
    return std::size_t(PemMap::texelCount(a.faceRes, a.mipLevels)) * a.samples.size() * 4 *
               sizeof(float) +
           distance + local;
}

// Every sample's six faces as array layers 6s .. 6s+5 of one RGBA32F array, the distant maps
// (alpha 1) or the local ones (premultiplied RGB, coverage). Throws Error naming the manifest
// when this GPU cannot hold that many layers.
gpu::Texture uploadMaps(const PemAsset& a, bool local) {
    GLint maxLayers = 0, maxSize = 0;
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    const int n = local ? a.localFaceRes : a.faceRes, layers = 6 * int(a.samples.size());
    if (layers > maxLayers || n > maxSize)
        throw Error(a.manifestPath, "samples",
                    std::to_string(a.samples.size()) + " maps of " + std::to_string(n) +
                        "^2 x 6 exceed this GPU's limits (" + std::to_string(maxSize) + "^2, " +
                        std::to_string(maxLayers) + " layers)");
    gpu::Texture maps = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
    const GLuint tex = maps.id();
    // The distant maps' MIP levels are the texture's own levels (texelFetch reads level k);
    // the local layer has one.
    const int levels = local ? 1 : a.mipLevels;
    glTextureStorage3D(tex, levels, GL_RGBA32F, n, n, layers);
    std::vector<float> rgba(std::size_t(PemMap::texelCount(n)) * 4);
    for (std::size_t s = 0; s < a.samples.size(); ++s) {
        const PemMap& m = local ? a.samples[s].local : a.samples[s].map;
        for (int level = 0; level < levels; ++level) {
            const int size = PemMap::levelRes(n, level);
            const std::size_t offset = std::size_t(PemMap::levelOffset(n, level));
            const std::size_t count = std::size_t(PemMap::texelCount(size));
            for (std::size_t t = 0; t < count; ++t)
                for (int c = 0; c < 4; ++c)
                    rgba[t * 4 + std::size_t(c)] =
                        c < 3 ? m.texels[offset + t][c] : (local ? m.alpha[t] : 1.f);
            // Faces are contiguous blocks in cube order: one upload of six layers per level.
            glTextureSubImage3D(tex, level, 0, 0, 6 * int(s), size, size, 6, GL_RGBA, GL_FLOAT,
                                rgba.data());
        }
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
gpu::Texture uploadDistance(const PemAsset& a) {
    const PemDistanceGeometry& g = *a.distance;
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (g.faceRes > maxSize)
        throw Error(a.manifestPath, "distance.face_res",
                    "a distance cube of " + std::to_string(g.faceRes) +
                        "^2 exceeds this GPU's limit (" + std::to_string(maxSize) + "^2)");
    gpu::Texture tex = gpu::Texture::create(GL_TEXTURE_2D_ARRAY);
    glTextureStorage3D(tex.id(), 1, GL_R32F, g.faceRes, g.faceRes, 6);
    glTextureSubImage3D(tex.id(), 0, 0, 0, 0, g.faceRes, g.faceRes, 6, GL_RED, GL_FLOAT,
                        g.distances.data());
    glTextureParameteri(tex.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return tex;
}

} // namespace

gpu::Program PemVariant::build() const {
    return buildReflectorProgram("components/reflection_probe/pem/shaders/pem_reflector.frag",
                                 {std::string("HAS_FRESNEL=") + (fresnel ? "1" : "0"),
                                  std::string("GEOMETRY_DISTANCE=") + (distance ? "1" : "0"),
                                  std::string("PEM_MIP=") + (mip ? "1" : "0"),
                                  std::string("HAS_LOCAL_LAYER=") + (local ? "1" : "0")},
                                 output);
}

PemProbeGpu PemStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) {
    PemProbeGpu g;
    g.asset = assets_.get(manifest.path, [&] { return readPemProbe(manifest); });
    g.maps = uploadMaps(*g.asset, false);
    ++stats.textureUploads;
    if (g.asset->localLayer) {
        g.local = uploadMaps(*g.asset, true);
        ++stats.textureUploads;
    }
    if (g.asset->distance) {
        g.distance = uploadDistance(*g.asset);
        ++stats.textureUploads;
    }
    return g;
}

void PemStore::applySettings(PemProbeGpu& g, const PemProbe& settings, ProbeFrameStats& stats) {
    g.params = pemParams(*g.asset, settings);
    g.block.upload(g.params);
    ++stats.parameterUploads;
}

std::size_t PemStore::gpuBytesOf(const PemProbeGpu& g) const {
    return mapBytes(*g.asset) + sizeof(glsl::PemParams);
}

const PemStore::HullBuffer& PemStore::hullBuffer(ecs::Entity reflector, const Mesh& mesh) {
    std::vector<const MeshData*> meshes;
    for (const Primitive& p : mesh.primitives)
        meshes.push_back(p.mesh.get());
    HullBuffer& h = hulls_[reflector];
    if (h.buffer && h.meshes == meshes) return h;
    h.meshes = std::move(meshes);
    h.flags = pemHullFlags(mesh);
    // A reflector without triangles still binds a (one-word) buffer.
    std::vector<std::uint32_t> words = h.flags.bits;
    if (words.empty()) words.push_back(0u);
    h.buffer = gpu::Buffer::create(words.data(), GLsizeiptr(words.size() * sizeof(std::uint32_t)));
    return h;
}

void PemStore::drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector, const Reflector& r,
                             const PemProbeGpu& g, const PemProbe&) {
    const Mesh* mesh = ctx.registry.find<Mesh>(reflector);
    const PemVariant v{r.fresnelF0 >= 0.f, ctx.output, g.asset->distance != nullptr,
                       g.asset->localLayer && mesh != nullptr, g.asset->mipLevels > 1};
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.filter().name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    glBindTextureUnit(1, g.maps.id());
    prog.setUniform("uPemMaps", 1);
    if (v.distance) {
        glBindTextureUnit(2, g.distance.id());
        prog.setUniform("uPemDistance", 2);
    }
    g.block.bind(glsl::kPemParamsBinding);
    prog.setUniform("uF0", r.fresnelF0);
    if (!v.local) {
        ctx.scene.drawEntity(reflector, prog);
        return;
    }
    glBindTextureUnit(3, g.local.id());
    prog.setUniform("uPemLocal", 3);
    const HullBuffer& hull = hullBuffer(reflector, *mesh);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(glsl::kPemHullBinding), hull.buffer.id());
    ctx.scene.drawEntity(reflector, prog, [&](std::size_t primitive) {
        prog.setUniform("uPemHullBase", int(hull.flags.firstTriangle[primitive]));
    });
}

} // namespace specula
