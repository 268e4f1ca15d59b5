#include "engine/render/scene_renderer.h"

#include "engine/core/error.h"
#include "engine/gpu/shader.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <string>

namespace specula {

namespace {

gpu::Texture makeTexture1x1(const glm::vec4& value) {
    gpu::Texture t = gpu::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, GL_RGBA32F, 1, 1);
    glTextureSubImage2D(t.id(), 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, &value[0]);
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

// Float storage keeps the texels bit-identical to the Image the CPU twins sample.
gpu::Texture uploadImage(const Image& img, GLenum wrapS, GLenum wrapT, const std::string& owner,
                         const std::string& field) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (img.width <= 0 || img.height <= 0 || img.width > maxSize || img.height > maxSize)
        throw Error(owner, field,
                    "expected an image of 1.." + std::to_string(maxSize) +
                        " texels per side, got " + std::to_string(img.width) + "x" +
                        std::to_string(img.height));
    if (img.channels < 1 || img.channels > 4 ||
        img.pixels.size() != std::size_t(img.width) * img.height * img.channels)
        throw Error(owner, field,
                    "expected 1 to 4 channels and width*height*channels floats, got " +
                        std::to_string(img.channels) + " channels, " +
                        std::to_string(img.pixels.size()) + " floats");
    static constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    gpu::Texture t = gpu::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, GL_RGBA32F, img.width, img.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    // Rows in stored order: uv (0, 0) lands on Image row 0, as glTF and sampling.h expect.
    glTextureSubImage2D(t.id(), 0, 0, 0, img.width, img.height, kFormats[img.channels - 1],
                        GL_FLOAT, img.pixels.data());
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GLint(wrapS));
    glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GLint(wrapT));
    // Missing channels read as 0 (alpha 1), the same as Image::rgba().
    const GLint swizzle[] = {GL_RED, img.channels > 1 ? GL_GREEN : GL_ZERO,
                             img.channels > 2 ? GL_BLUE : GL_ZERO,
                             img.channels > 3 ? GL_ALPHA : GL_ONE};
    glTextureParameteriv(t.id(), GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    return t;
}

} // namespace

SceneRenderer::SceneRenderer()
    : sceneProgram_(gpu::buildProgram(gpu::ShaderSource::file("engine/render/shaders/scene.vert"),
                                      gpu::ShaderSource::file("engine/render/shaders/scene.frag"))),
      skyProgram_(gpu::buildProgram(gpu::ShaderSource::file("engine/render/shaders/sky.vert"),
                                    gpu::ShaderSource::file("engine/render/shaders/sky.frag"))),
      emptyVao_(gpu::VertexArray::create()), white_(makeTexture1x1(glm::vec4(1.f))),
      sky_(makeTexture1x1(glm::vec4(0.f, 0.f, 0.f, 1.f))) {
    sceneProgram_.setUniform("uBaseColorTexture", kBaseColorUnit);
    skyProgram_.setUniform("uSky", 0);
}

SceneRenderer::~SceneRenderer() = default;

SceneRenderer::GpuMesh& SceneRenderer::meshFor(const std::shared_ptr<const MeshData>& data,
                                               const std::string& meshName) {
    auto it = meshes_.find(data.get());
    if (it != meshes_.end()) {
        it->second.used = true;
        return it->second;
    }
    const MeshData& m = *data;
    const std::size_t n = m.positions.size();
    const std::string owner = "mesh \"" + meshName + "\"";
    if (!m.normals.empty() && m.normals.size() != n)
        throw Error(owner, "normals",
                    "expected " + std::to_string(n) + " (one per position), got " +
                        std::to_string(m.normals.size()));
    if (!m.uvs.empty() && m.uvs.size() != n)
        throw Error(owner, "uvs",
                    "expected " + std::to_string(n) + " (one per position) or none, got " +
                        std::to_string(m.uvs.size()));
    for (std::uint32_t i : m.indices)
        if (i >= n)
            throw Error(owner, "indices",
                        "expected indices below the vertex count " + std::to_string(n) +
                            ", found " + std::to_string(i));

    // Interleaved position, normal, uv: one buffer, one binding, 32-byte stride.
    std::vector<float> interleaved(n * 8, 0.f);
    for (std::size_t i = 0; i < n; ++i) {
        float* v = &interleaved[i * 8];
        v[0] = m.positions[i].x, v[1] = m.positions[i].y, v[2] = m.positions[i].z;
        if (!m.normals.empty()) v[3] = m.normals[i].x, v[4] = m.normals[i].y, v[5] = m.normals[i].z;
        if (!m.uvs.empty()) v[6] = m.uvs[i].x, v[7] = m.uvs[i].y;
    }
    GpuMesh g;
    g.source = data;
    g.used = true;
    g.vertices = gpu::Buffer::create(interleaved.data(), GLsizeiptr(interleaved.size() * 4));
    g.vao = gpu::VertexArray::create();
    const GLuint vao = g.vao.id();
    glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, 8 * sizeof(float));
    const GLuint sizes[] = {3, 3, 2}, offsets[] = {0, 3, 6};
    for (GLuint loc = 0; loc < 3; ++loc) {
        glEnableVertexArrayAttrib(vao, loc);
        glVertexArrayAttribFormat(vao, loc, GLint(sizes[loc]), GL_FLOAT, GL_FALSE,
                                  offsets[loc] * sizeof(float));
        glVertexArrayAttribBinding(vao, loc, 0);
    }
    g.indexed = !m.indices.empty();
    if (g.indexed) {
        g.indices = gpu::Buffer::create(m.indices.data(), GLsizeiptr(m.indices.size() * 4));
        glVertexArrayElementBuffer(vao, g.indices.id());
        g.count = GLsizei(m.indices.size());
    } else {
        g.count = GLsizei(n);
    }
    return meshes_.emplace(data.get(), std::move(g)).first->second;
}

GLuint SceneRenderer::textureFor(const std::shared_ptr<const Image>& image,
                                 const std::string& materialName) {
    if (!image || image->empty()) return white_.id();
    auto it = textures_.find(image.get());
    if (it == textures_.end()) {
        GpuTexture t;
        t.source = image;
        t.texture = uploadImage(*image, GL_REPEAT, GL_REPEAT, "material \"" + materialName + "\"",
                                "baseColorTexture");
        it = textures_.emplace(image.get(), std::move(t)).first;
    }
    it->second.used = true;
    return it->second.texture.id();
}

void SceneRenderer::sync(ecs::Registry& registry) {
    registry_ = &registry;
    for (auto& [k, m] : meshes_)
        m.used = false;
    for (auto& [k, t] : textures_)
        t.used = false;
    draws_.clear();
    order_.clear();

    registry.view<Mesh, Transform>().each([&](ecs::Entity e, Mesh& mesh, Transform&) {
        std::vector<DrawItem> items;
        for (std::size_t k = 0; k < mesh.primitives.size(); ++k) {
            const Primitive& p = mesh.primitives[k];
            if (!p.mesh || p.mesh->positions.empty()) continue;
            DrawItem item;
            item.primitive = k;
            item.mesh = &meshFor(p.mesh, mesh.name);
            item.material = p.material;
            item.texture = p.material ? textureFor(p.material->baseColorTexture, p.material->name)
                                      : white_.id();
            items.push_back(std::move(item));
        }
        draws_.emplace(e, std::move(items));
        order_.push_back(e);
    });

    std::erase_if(meshes_, [](const auto& kv) { return !kv.second.used; });
    std::erase_if(textures_, [](const auto& kv) { return !kv.second.used; });
}

void SceneRenderer::setSky(const Image& equirect) {
    if (equirect.empty()) {
        clearSky();
        return;
    }
    // T clamps: the top row is the zenith and the bottom the nadir, which must not blend.
    sky_ = uploadImage(equirect, GL_REPEAT, GL_CLAMP_TO_EDGE, "sky", "equirect image");
    hasSky_ = true;
}

void SceneRenderer::clearSky() {
    sky_ = makeTexture1x1(glm::vec4(0.f, 0.f, 0.f, 1.f));
    hasSky_ = false;
}

void SceneRenderer::setCameraUniforms(gpu::Program& program, const CameraView& camera) {
    program.setUniform("uViewProj", camera.viewProj());
    program.setUniform("uEye", camera.eye());
}

void SceneRenderer::drawSky(const CameraView& camera) {
    // Inverse of proj * (view without translation): the reconstructed direction is then
    // eye-relative, so large eye coordinates cannot cancel away its precision.
    const glm::mat4 rotationOnly = glm::mat4(glm::mat3(camera.view));
    skyProgram_.setUniform("uInvViewProjRot", glm::inverse(camera.proj * rotationOnly));
    GLint viewport[4];
    glGetIntegerv(GL_VIEWPORT, viewport);
    skyProgram_.setUniform("uViewport",
                           glm::vec4(viewport[0], viewport[1], viewport[2], viewport[3]));
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    skyProgram_.use();
    glBindTextureUnit(0, sky_.id());
    glBindVertexArray(emptyVao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
}

void SceneRenderer::drawEntity(ecs::Entity entity, gpu::Program& program,
                               const std::function<void(std::size_t)>& beforeDraw) {
    if (!registry_ || !registry_->valid(entity)) return;
    const auto it = draws_.find(entity);
    const Transform* transform = registry_->find<Transform>(entity);
    if (it == draws_.end() || !transform) return;
    const glm::mat4& world = transform->world;
    program.setUniform("uModel", world);
    program.setUniform("uNormalMatrix", glm::inverseTranspose(glm::mat3(world)));
    program.setUniform("uBaseColorTexture", kBaseColorUnit);
    program.use();
    for (const DrawItem& item : it->second) {
        program.setUniform("uBaseColorFactor",
                           item.material ? item.material->baseColorFactor : glm::vec4(1.f));
        glBindTextureUnit(kBaseColorUnit, item.texture);
        glBindVertexArray(item.mesh->vao.id());
        if (beforeDraw) beforeDraw(item.primitive);
        if (item.mesh->indexed)
            glDrawElements(GL_TRIANGLES, item.mesh->count, GL_UNSIGNED_INT, nullptr);
        else
            glDrawArrays(GL_TRIANGLES, 0, item.mesh->count);
    }
}

void SceneRenderer::drawEntities(gpu::Program& program,
                                 const std::function<bool(ecs::Entity)>& skip) {
    for (ecs::Entity e : order_)
        if (!skip || !skip(e)) drawEntity(e, program);
}

void SceneRenderer::render(const CameraView& camera, gpu::RenderTarget& target,
                           const std::function<bool(ecs::Entity)>& skip) {
    target.bind();
    target.clear(glm::vec4(0.f, 0.f, 0.f, 1.f), 1.f);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    // Culling stays off: rooms are closed meshes seen from inside.
    glDisable(GL_CULL_FACE);
    drawSky(camera);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    setCameraUniforms(sceneProgram_, camera);
    drawEntities(sceneProgram_, skip);
}

} // namespace specula
