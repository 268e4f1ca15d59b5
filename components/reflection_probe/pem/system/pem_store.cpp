#include "pem_store.h"

#include "engine/core/error.h"
#include "engine/gpu/shader.h"

#include <vector>

namespace specula {

gpu::Program PemVariant::build() const {
    return buildReflectorProgram("components/reflection_probe/pem/shaders/pem_reflector.frag",
                                 {std::string("HAS_FRESNEL=") + (fresnel ? "1" : "0"),
                                  std::string("GEOMETRY_DISTANCE=") + (distance ? "1" : "0"),
                                  std::string("PEM_MIP=") + (mip ? "1" : "0"),
                                  std::string("HAS_LOCAL_LAYER=") + (local ? "1" : "0")},
                                 output);
}

PemGpuProbe PemStore::loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) {
    PemGpuProbe g =
        PemGpuProbe::load(assets_.get(manifest.path, [&] { return readPemProbe(manifest); }));
    stats.textureUploads += 1 + (g.local ? 1 : 0) + (g.distance ? 1 : 0);
    return g;
}

void PemStore::applySettings(PemGpuProbe& g, const PemProbe& settings, ProbeFrameStats& stats) {
    g.applySettings(settings);
    ++stats.parameterUploads;
}

std::size_t PemStore::gpuBytesOf(const PemGpuProbe& g) const {
    return g.gpuBytes();
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
                             const PemGpuProbe& g, const PemProbe&) {
    const Mesh* mesh = ctx.registry.find<Mesh>(reflector);
    const PemVariant v{r.fresnelF0 >= 0.f, ctx.output, g.asset->distance != nullptr,
                       g.asset->localLayer && mesh != nullptr, g.asset->mipLevels > 1};
    gpu::Program& prog = variants_.get(v);
    ctx.stats.drew(v.filter().name());
    prog.use();
    SceneRenderer::setCameraUniforms(prog, ctx.camera);
    g.bindTo(prog.id(), PemBindings{}, v.local);
    prog.setUniform("uF0", r.fresnelF0);
    if (!v.local) {
        ctx.scene.drawEntity(reflector, prog);
        return;
    }
    const HullBuffer& hull = hullBuffer(reflector, *mesh);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(glsl::kPemHullBinding), hull.buffer.id());
    ctx.scene.drawEntity(reflector, prog, [&](std::size_t primitive) {
        prog.setUniform("uPemHullBase", int(hull.flags.firstTriangle[primitive]));
    });
}

} // namespace specula
