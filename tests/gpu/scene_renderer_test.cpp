#include "engine/core/error.h"
#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"
#include "engine/math/shading.h"
#include "engine/render/scene_renderer.h"
#include "engine/scene/transform_system.h"
#include "gl_test_context.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace specula {
namespace {

using SceneRendererTest = test::GlTest;

constexpr int kW = 32, kH = 24;

// A unit quad in the XY plane facing +Z, uv (0, 0) at the top-left as glTF lays it out.
std::shared_ptr<MeshData> quadMesh(float half) {
    auto m = std::make_shared<MeshData>();
    m->positions = {{-half, -half, 0.f}, {half, -half, 0.f}, {half, half, 0.f}, {-half, half, 0.f}};
    m->normals.assign(4, glm::vec3(0.f, 0.f, 1.f));
    m->uvs = {{0.f, 1.f}, {1.f, 1.f}, {1.f, 0.f}, {0.f, 0.f}};
    m->indices = {0, 1, 2, 0, 2, 3};
    m->boundsMin = {-half, -half, 0.f};
    m->boundsMax = {half, half, 0.f};
    return m;
}

ecs::Entity addQuad(ecs::Registry& reg, std::shared_ptr<const MeshData> mesh, glm::vec4 colour,
                    glm::vec3 at, std::shared_ptr<const Image> texture = nullptr) {
    const ecs::Entity e = reg.create();
    auto mat = std::make_shared<MaterialData>();
    mat->baseColorFactor = colour;
    mat->baseColorTexture = std::move(texture);
    mat->name = "quad material";
    reg.emplace<Mesh>(e, Mesh{"quad", {Primitive{std::move(mesh), mat}}});
    Transform t;
    t.translation = at;
    reg.emplace<Transform>(e, t);
    return e;
}

CameraView frontCamera() {
    return CameraView::lookAt({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, {0.f, 1.f, 0.f}, 1.0f, kW, kH);
}

TEST_F(SceneRendererTest, QuadMatchesCpuShading) {
    ecs::Registry reg;
    const glm::vec4 base(0.8f, 0.5f, 0.2f, 1.f);
    // Tilted so the sun term is neither 0 nor 1; a uniform scale keeps the normal unit.
    const ecs::Entity e = addQuad(reg, quadMesh(1.f), base, {0.f, 0.f, -3.f});
    reg.get<Transform>(e).rotation = glm::angleAxis(0.6f, glm::normalize(glm::vec3(1.f, 1.f, 0.f)));
    reg.get<Transform>(e).scale = glm::vec3(0.8f);
    updateWorldTransforms(reg);

    SceneRenderer renderer;
    renderer.sync(reg);
    gpu::RenderTarget target(kW, kH);
    renderer.render(frontCamera(), target);
    const Image img = target.readback();

    const glm::vec3 n = glm::normalize(glm::mat3(reg.get<Transform>(e).world) * glm::vec3(0, 0, 1));
    const glm::vec3 expected = glsl::shadeSurface(glm::vec3(base), n);
    const glm::vec4 centre = img.rgba(kW / 2, kH / 2);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(centre[c], expected[c], 1e-3f) << c;
    EXPECT_EQ(centre.a, 1.f);
    EXPECT_EQ(img.rgba(0, 0), glm::vec4(0.f, 0.f, 0.f, 1.f)); // corner: black sky
}

TEST_F(SceneRendererTest, TextureRowZeroIsUvZero) {
    ecs::Registry reg;
    auto tex = std::make_shared<Image>(1, 2, 4);
    *reinterpret_cast<glm::vec4*>(tex->at(0, 0)) = {1.f, 0.f, 0.f, 1.f}; // row 0: red
    *reinterpret_cast<glm::vec4*>(tex->at(0, 1)) = {0.f, 1.f, 0.f, 1.f}; // row 1: green
    addQuad(reg, quadMesh(1.f), glm::vec4(1.f), {0.f, 0.f, -1.f}, tex);
    updateWorldTransforms(reg);
    SceneRenderer renderer;
    renderer.sync(reg);
    EXPECT_EQ(renderer.gpuTextureCount(), 1u);
    gpu::RenderTarget target(kW, kH);
    renderer.render(frontCamera(), target);
    const Image img = target.readback();
    // The quad fills the view; uv v = 0 (image row 0, red) at its top.
    const glm::vec4 top = img.rgba(kW / 2, 1), bottom = img.rgba(kW / 2, kH - 2);
    EXPECT_GT(top.r, top.g);
    EXPECT_GT(bottom.g, bottom.r);
}

TEST_F(SceneRendererTest, SkipMovesAndResync) {
    ecs::Registry reg;
    auto mesh = quadMesh(0.5f);
    const ecs::Entity a = addQuad(reg, mesh, glm::vec4(1.f, 0.f, 0.f, 1.f), {0.f, 0.f, -2.f});
    const ecs::Entity b = addQuad(reg, mesh, glm::vec4(0.f, 1.f, 0.f, 1.f), {0.f, 0.f, -4.f});
    updateWorldTransforms(reg);
    SceneRenderer renderer;
    renderer.sync(reg);
    EXPECT_EQ(renderer.gpuMeshCount(), 1u); // shared MeshData, one GPU copy
    EXPECT_EQ(renderer.entities().size(), 2u);
    gpu::RenderTarget target(kW, kH);
    const CameraView cam = frontCamera();
    const int cx = kW / 2, cy = kH / 2;

    renderer.render(cam, target);
    EXPECT_GT(target.readback().rgba(cx, cy).r, 0.1f); // a is in front

    renderer.render(cam, target, [&](ecs::Entity e) { return e == a; });
    EXPECT_GT(target.readback().rgba(cx, cy).g, 0.1f); // b shows through

    // Moving needs no re-sync: the world matrix is read at draw time.
    reg.get<Transform>(a).translation = {0.f, 100.f, -2.f};
    reg.get<Transform>(b).translation = {0.f, 100.f, -4.f};
    updateWorldTransforms(reg);
    renderer.render(cam, target);
    EXPECT_EQ(target.readback().rgba(cx, cy), glm::vec4(0.f, 0.f, 0.f, 1.f));

    reg.destroy(a);
    reg.destroy(b);
    renderer.sync(reg);
    EXPECT_FALSE(renderer.contains(a));
    EXPECT_EQ(renderer.gpuMeshCount(), 0u);
}

TEST_F(SceneRendererTest, MalformedMeshNamesTheMeshAndField) {
    ecs::Registry reg;
    auto mesh = quadMesh(1.f);
    mesh->indices.push_back(9);
    addQuad(reg, mesh, glm::vec4(1.f), {0.f, 0.f, -1.f});
    SceneRenderer renderer;
    try {
        renderer.sync(reg);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), "mesh \"quad\"");
        EXPECT_EQ(e.field(), "indices");
    }
}

// The sky pass against its CPU twin, sampleBilinear(equirectUv(dir)) with the GPU's wrap
// modes, at every pixel of two views (one level, one tilted up towards the zenith).
// Tolerance 2e-3, because: GPUs quantise GL_LINEAR blend weights (typically 8 bits of
// sub-texel position), which moves a result by up to the largest step between neighbouring
// texels (< 0.1 in this image) / 256 ~ 4e-4; both sides rebuild the pixel direction from
// float matrices (~1e-6 rad against a texel of ~0.1 rad), and GLSL atan/acos are not
// correctly rounded. llvmpipe measures ~5e-5.
TEST_F(SceneRendererTest, SkyMatchesCpuEquirectLookup) {
    constexpr int kSkyW = 64, kSkyH = 32;
    constexpr float kTwoPi = 6.2831853f, kPi = 3.14159265f;
    Image sky(kSkyW, kSkyH, 4);
    for (int y = 0; y < kSkyH; ++y)
        for (int x = 0; x < kSkyW; ++x) {
            const float u = (float(x) + 0.5f) / kSkyW, v = (float(y) + 0.5f) / kSkyH;
            float* p = sky.at(x, y);
            p[0] = 0.5f + 0.5f * std::sin(kTwoPi * u);
            p[1] = v;
            p[2] = 0.5f + 0.5f * std::cos(2.f * kTwoPi * u) * std::sin(kPi * v);
            p[3] = 1.f;
        }
    ecs::Registry reg;
    SceneRenderer renderer;
    renderer.sync(reg);
    renderer.setSky(sky);
    ASSERT_TRUE(renderer.hasSky());
    gpu::RenderTarget target(kW, kH);

    const CameraView views[] = {
        CameraView::lookAt({1.f, 2.f, 3.f}, {1.f, 2.f, 3.f - 1.f}, {0, 1, 0}, 1.2f, kW, kH),
        CameraView::lookAt({0.f, 0.f, 0.f}, {0.3f, 0.8f, 0.4f}, {0, 1, 0}, 1.0f, kW, kH),
    };
    float worst = 0.f;
    for (const CameraView& cam : views) {
        renderer.render(cam, target);
        const Image img = target.readback();
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                glm::vec3 origin, dir;
                cam.primaryRay(x, y, origin, dir);
                const glm::vec4 cpu =
                    sampleBilinear(sky, glsl::equirectUv(dir), Wrap::Repeat, Wrap::Clamp);
                const glm::vec4 gpu = img.rgba(x, y);
                for (int c = 0; c < 3; ++c)
                    worst = std::max(worst, std::abs(cpu[c] - gpu[c]));
                ASSERT_EQ(gpu.a, 1.f);
            }
    }
    RecordProperty("worst_abs_error", std::to_string(worst));
    EXPECT_LT(worst, 2e-3f);

    renderer.clearSky();
    renderer.render(views[0], target);
    EXPECT_EQ(target.readback().rgba(3, 3), glm::vec4(0.f, 0.f, 0.f, 1.f));
}

} // namespace
} // namespace specula
