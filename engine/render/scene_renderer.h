#pragma once
// Rasterises the environment of a scene: every entity with Mesh + Transform, shaded with
// the house shading (engine/math/shading.glsl.h), over an equirectangular sky. Output is
// linear float radiance, alpha 1. The same picture the probe bake and the ray tracer see.
//
// The renderer owns the GPU copies of meshes, textures and the sky; the components hold no
// GL handles. GPU meshes and textures are shared between entities that share the same
// MeshData / Image (keyed by pointer identity, the shared_ptr kept alive while cached).
//
// Contract for any Program drawn through drawEntity() / drawEntities() (a reflection pass
// or a probe bake reuses the geometry with its own shaders):
//   layout(location = 0) in vec3 aPosition;   object space
//   layout(location = 1) in vec3 aNormal;     object space (zero when the mesh has none)
//   layout(location = 2) in vec2 aUv;         glTF convention: (0, 0) is the first image row
//                                             (zero when the mesh has none)
//   uniform mat4 uModel;                      Transform::world, read at draw time
//   uniform mat3 uNormalMatrix;               transpose(inverse(mat3(uModel)))
//   uniform vec4 uBaseColorFactor;            MaterialData::baseColorFactor (1 when none)
//   uniform sampler2D uBaseColorTexture;      unit kBaseColorUnit; 1x1 white when none;
//                                             GL_LINEAR, no mipmaps, GL_REPEAT (matches
//                                             sampleBilinear(..., Wrap::Repeat))
// Camera uniforms, set by setCameraUniforms():
//   uniform mat4 uViewProj;                   CameraView::viewProj() (OpenGL clip space)
//   uniform vec3 uEye;                        CameraView::eye(), world space
// Uniforms a program does not declare are ignored.
#include "engine/ecs/registry.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/render_target.h"
#include "engine/image/image.h"
#include "engine/math/camera.h"
#include "engine/scene/components.h"

#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

namespace specula {

class SceneRenderer {
public:
    static constexpr int kBaseColorUnit = 0;

    SceneRenderer(); // needs a current GL 4.5 context; compiles the scene and sky programs
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // Brings the GPU copies in line with the registry: uploads what is new, drops what is
    // gone. Transforms are not copied: each draw reads Transform::world from this registry,
    // so moving objects need no re-sync (run updateWorldTransforms() before drawing). The
    // registry must outlive the renderer's use of it until the next sync().
    // Throws specula::Error on malformed mesh data (attribute counts, index range).
    void sync(ecs::Registry& registry);

    // Linear float equirect panorama (row 0 = zenith, see equirectUv()). GL_LINEAR, no
    // mipmaps, S repeat, T clamp to edge (CPU twin: sampleBilinear(img, uv, Repeat, Clamp)).
    void setSky(const Image& equirect);
    void clearSky(); // the sky is black again
    bool hasSky() const { return hasSky_; }
    const gpu::Texture& skyTexture() const { return sky_; }

    // Clears `target` (depth 1, colour black), draws the sky, then every synced entity for
    // which `skip` is false (or all when `skip` is empty). Leaves `target` bound.
    void render(const CameraView& camera, gpu::RenderTarget& target,
                const std::function<bool(ecs::Entity)>& skip = {});

    // The sky alone into the bound framebuffer and viewport, with depth test and depth
    // writes off (it lies at the far plane).
    void drawSky(const CameraView& camera);

    // Draws the entity's primitives with `program` (see the contract above) into the bound
    // framebuffer with the current GL state. Does nothing for an entity not synced or no
    // longer alive. The caller sets the camera uniforms.
    // beforeDraw (when given) runs before each primitive's draw call with the primitive's index
    // in Mesh::primitives: per-draw state such as a per-primitive uniform (gl_PrimitiveID
    // restarts at every draw).
    void drawEntity(ecs::Entity entity, gpu::Program& program,
                    const std::function<void(std::size_t)>& beforeDraw = {});
    void drawEntities(gpu::Program& program, const std::function<bool(ecs::Entity)>& skip = {});

    static void setCameraUniforms(gpu::Program& program, const CameraView& camera);

    bool contains(ecs::Entity entity) const { return draws_.count(entity) != 0; }
    const std::vector<ecs::Entity>& entities() const { return order_; }
    std::size_t gpuMeshCount() const { return meshes_.size(); }
    std::size_t gpuTextureCount() const { return textures_.size(); }

private:
    struct GpuMesh {
        std::shared_ptr<const MeshData> source; // keeps the cache key's address unique
        gpu::Buffer vertices, indices;
        gpu::VertexArray vao;
        GLsizei count = 0;
        bool indexed = false;
        bool used = false;
    };
    struct GpuTexture {
        std::shared_ptr<const Image> source;
        gpu::Texture texture;
        bool used = false;
    };
    struct DrawItem {
        const GpuMesh* mesh = nullptr;
        std::shared_ptr<const MaterialData> material;
        GLuint texture = 0;
        std::size_t primitive = 0; // index in Mesh::primitives
    };

    GpuMesh& meshFor(const std::shared_ptr<const MeshData>& data, const std::string& meshName);
    GLuint textureFor(const std::shared_ptr<const Image>& image, const std::string& materialName);

    ecs::Registry* registry_ = nullptr;
    gpu::Program sceneProgram_, skyProgram_;
    gpu::VertexArray emptyVao_; // core profile draws need a VAO even without attributes
    gpu::Texture white_, sky_;
    bool hasSky_ = false;
    std::unordered_map<const MeshData*, GpuMesh> meshes_;
    std::unordered_map<const Image*, GpuTexture> textures_;
    std::unordered_map<ecs::Entity, std::vector<DrawItem>> draws_;
    std::vector<ecs::Entity> order_; // sync order, so draws are deterministic
};

} // namespace specula
