#include "engine/math/shading.h"
#include "engine/raytrace/ground_truth.h"

#include "engine/core/glsl_host.h"
#include "engine/image/sampling.h"
#include "raytrace/test_scenes.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace specula {
namespace {

using namespace testscenes;

void expectColor(glm::vec3 actual, glm::vec3 expected, float tol, const char* what) {
    EXPECT_NEAR(actual.r, expected.r, tol) << what;
    EXPECT_NEAR(actual.g, expected.g, tol) << what;
    EXPECT_NEAR(actual.b, expected.b, tol) << what;
}

glm::vec3 pixel(const Image& img, int x, int y) {
    return glm::vec3(img.rgba(x, y));
}

// The pixel whose centre ray goes closest to the world point p.
glm::ivec2 projectToPixel(const CameraView& cam, glm::vec3 p) {
    const glm::vec4 clip = cam.viewProj() * glm::vec4(p, 1.f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    return {int(std::floor((ndc.x + 1.f) * 0.5f * float(cam.width))),
            int(std::floor((1.f - ndc.y) * 0.5f * float(cam.height)))};
}

TEST(GroundTruth, MirrorSphereUnderUniformSkyReturnsSky) {
    const glm::vec3 skyColor(0.2f, 0.4f, 0.8f);
    const Image sky = solidImage(16, 8, skyColor);
    ecs::Registry reg;
    const ecs::Entity ball = addMesh(reg, sphere(1.f), glm::vec3(1.f, 0.f, 0.f));
    updateWorldTransforms(reg);
    TraceOptions opt;
    opt.mirrors = {ball};
    opt.sky = &sky;
    const GroundTruthTracer tracer(reg, opt);
    const CameraView cam =
        CameraView::lookAt({0.f, 0.5f, 4.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 0.8f, 48, 40);
    const GroundTruthImage gt = tracer.render(cam);
    ASSERT_EQ(gt.color.width, 48);
    ASSERT_EQ(gt.color.height, 40);
    int onMirror = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            expectColor(pixel(gt.color, x, y), skyColor, 1e-5f, "sky everywhere");
            if (gt.mirrorMask.at(x, y)[0] > 0.5f) {
                ++onMirror;
                EXPECT_TRUE(std::isfinite(gt.depth.at(x, y)[0]));
                EXPECT_GT(gt.depth.at(x, y)[0], 2.f);
                EXPECT_LT(gt.depth.at(x, y)[0], 4.2f);
            } else {
                EXPECT_TRUE(std::isinf(gt.depth.at(x, y)[0]));
            }
        }
    EXPECT_GT(onMirror, 200);
    EXPECT_EQ(gt.mirrorMask.at(24, 20)[0], 1.f);
    EXPECT_EQ(gt.mirrorMask.at(0, 0)[0], 0.f);
}

TEST(GroundTruth, MirrorPlaneReflectsColouredQuadAtPredictedPixel) {
    const glm::vec3 skyColor(0.1f, 0.1f, 0.3f);
    const Image sky = solidImage(8, 4, skyColor);
    const glm::vec3 quadColor(0.9f, 0.3f, 0.1f);
    ecs::Registry reg;
    const ecs::Entity mirror =
        addMesh(reg, quad({-10.f, 0.f, 10.f}, {20.f, 0.f, 0.f}, {0.f, 0.f, -20.f}));
    // Faces +Z, towards the camera side; spans x in [-3, 3], y in [0.5, 4] at z = -5.
    addMesh(reg, quad({-3.f, 0.5f, -5.f}, {6.f, 0.f, 0.f}, {0.f, 3.5f, 0.f}), quadColor);
    updateWorldTransforms(reg);
    TraceOptions opt;
    opt.mirrors = {mirror};
    opt.sky = &sky;
    const GroundTruthTracer tracer(reg, opt);
    const CameraView cam =
        CameraView::lookAt({0.f, 1.f, 5.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 1.0f, 64, 64);
    const GroundTruthImage gt = tracer.render(cam);

    // The mirror image of the quad point (0.4, 2, -5) lies at (0.4, -2, -5).
    const glm::ivec2 p = projectToPixel(cam, {0.4f, -2.f, -5.f});
    ASSERT_TRUE(p.x >= 0 && p.x < cam.width && p.y >= 0 && p.y < cam.height);
    EXPECT_EQ(gt.mirrorMask.at(p.x, p.y)[0], 1.f);
    const glm::vec3 expected = glsl::shadeSurface(quadColor, glm::vec3(0.f, 0.f, 1.f));
    expectColor(pixel(gt.color, p.x, p.y), expected, 1e-5f, "reflected quad");

    // Above the quad's top edge the reflection sees the sky.
    const glm::ivec2 q = projectToPixel(cam, {0.4f, -6.f, -5.f});
    ASSERT_TRUE(q.x >= 0 && q.x < cam.width && q.y >= 0 && q.y < cam.height);
    EXPECT_EQ(gt.mirrorMask.at(q.x, q.y)[0], 1.f);
    expectColor(pixel(gt.color, q.x, q.y), skyColor, 1e-5f, "reflected sky");

    // And the render agrees with radiance() for the same primary ray.
    glm::vec3 o, d;
    cam.primaryRay(p.x, p.y, o, d);
    expectColor(tracer.radiance(o, d), pixel(gt.color, p.x, p.y), 0.f, "render == radiance");
}

// Mirror A on the floor sends the ray to mirror B (a wall at x = 2), which sends it up into
// the sky; with B invisible, the ray goes on to the red wall at x = 4.
struct TwoMirrors {
    ecs::Registry reg;
    ecs::Entity a, b;
    Image sky = solidImage(8, 4, {0.f, 0.f, 1.f});
    const glm::vec3 red{1.f, 0.f, 0.f};

    TwoMirrors() {
        a = addMesh(reg, quad({-5.f, 0.f, 5.f}, {10.f, 0.f, 0.f}, {0.f, 0.f, -10.f}));
        b = addMesh(reg, quad({2.f, 1.f, 1.f}, {0.f, 0.f, -2.f}, {0.f, 2.f, 0.f}));
        addMesh(reg, quad({4.f, 0.f, 2.f}, {0.f, 8.f, 0.f}, {0.f, 0.f, -4.f}), red); // faces -x
        updateWorldTransforms(reg);
    }
    TraceOptions options(bool environmentOnly) const {
        TraceOptions o;
        o.mirrors = {a, b};
        o.sky = &sky;
        o.environmentOnly = environmentOnly;
        return o;
    }
};

TEST(GroundTruth, EnvironmentOnlyMakesTheSecondMirrorInvisible) {
    TwoMirrors s;
    const glm::vec3 o(-2.f, 2.f, 0.f), d = glm::normalize(glm::vec3(1.f, -1.f, 0.f));
    const GroundTruthTracer full(s.reg, s.options(false));
    const GroundTruthTracer envOnly(s.reg, s.options(true));
    expectColor(full.radiance(o, d), glm::vec3(0.f, 0.f, 1.f), 1e-6f, "full: B reflects sky");
    expectColor(envOnly.radiance(o, d), glsl::shadeSurface(s.red, glm::vec3(-1.f, 0.f, 0.f)), 1e-6f,
                "environment only: through B to the red wall");
    // A primary ray still sees mirror B itself.
    const glm::vec3 o2(0.f, 2.f, 0.f), d2(1.f, 0.f, 0.f);
    expectColor(envOnly.radiance(o2, d2), glm::vec3(0.f, 0.f, 1.f), 1e-6f, "primary sees B");
}

TEST(GroundTruth, BounceLimitAndTint) {
    TwoMirrors s;
    const glm::vec3 o(-2.f, 2.f, 0.f), d = glm::normalize(glm::vec3(1.f, -1.f, 0.f));
    TraceOptions opt = s.options(false);
    opt.maxBounces = 1; // A reflects, B is out of bounces
    expectColor(GroundTruthTracer(s.reg, opt).radiance(o, d), glm::vec3(0.f), 0.f, "one bounce");
    opt.maxBounces = 0;
    expectColor(GroundTruthTracer(s.reg, opt).radiance(o, d), glm::vec3(0.f), 0.f, "none");
    opt.maxBounces = 4;
    opt.mirrorTint = [&](ecs::Entity e) {
        return e == s.a ? glm::vec3(0.5f) : glm::vec3(1.f, 1.f, 0.25f);
    };
    expectColor(GroundTruthTracer(s.reg, opt).radiance(o, d), glm::vec3(0.f, 0.f, 0.125f), 1e-6f,
                "tints multiply");
}

TEST(GroundTruth, TraceEnvironmentSkipsMirrorsAndFiltersLayers) {
    TwoMirrors s;
    const GroundTruthTracer tracer(s.reg, s.options(false));
    // From (0, 2, 0) along +x: B (a mirror) at 2 is not environment; the red wall is at 4.
    EnvSample e = tracer.traceEnvironment({0.f, 2.f, 0.f}, {3.f, 0.f, 0.f});
    ASSERT_TRUE(e.hit);
    EXPECT_NEAR(e.distance, 4.f, 1e-5f);
    expectColor(e.radiance, glsl::shadeSurface(s.red, glm::vec3(-1.f, 0.f, 0.f)), 1e-6f, "wall");
    const std::function<bool(ecs::Entity)> nothing = [](ecs::Entity) { return false; };
    e = tracer.traceEnvironment({0.f, 2.f, 0.f}, {1.f, 0.f, 0.f}, &nothing);
    EXPECT_FALSE(e.hit);
    EXPECT_TRUE(std::isinf(e.distance));
    expectColor(e.radiance, glm::vec3(0.f, 0.f, 1.f), 0.f, "sky on a miss");
}

TEST(GroundTruth, SkyIsSampledLikeTheGpu) {
    Image sky(8, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            sky.at(x, y)[0] = float(x) / 8.f;
            sky.at(x, y)[1] = float(y) / 4.f;
            sky.at(x, y)[2] = 0.5f;
        }
    ecs::Registry reg;
    TraceOptions opt;
    opt.sky = &sky;
    const GroundTruthTracer tracer(reg, opt);
    for (const glm::vec3 d : {glm::vec3(0.f, 1.f, 0.f), glm::vec3(0.3f, -0.2f, -1.f),
                              glm::vec3(-0.01f, 0.1f, 1.f), glm::vec3(0.01f, 0.1f, 1.f)}) {
        const glm::vec3 expected(
            sampleBilinear(sky, glsl::equirectUv(glm::normalize(d)), Wrap::Repeat, Wrap::Clamp));
        expectColor(tracer.radiance({0.f, 0.f, 0.f}, d), expected, 1e-6f, "sky");
    }
    // Across the seam behind the viewer (u = 0 / 1) the lookup wraps: both sides agree.
    const glm::vec3 left = tracer.sky({-1e-4f, 0.f, 1.f}), right = tracer.sky({1e-4f, 0.f, 1.f});
    expectColor(left, right, 1e-3f, "seam");
    // Without a sky, misses are black.
    const GroundTruthTracer dark(reg, TraceOptions{});
    expectColor(dark.radiance({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}), glm::vec3(0.f), 0.f, "no sky");
}

TEST(GroundTruth, DegenerateGeometryRendersWithoutNaN) {
    ecs::Registry reg;
    auto m = std::make_shared<MeshData>();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    m->positions = {{-1.f, -1.f, 0.f}, {1.f, -1.f, 0.f},  {1.f, 1.f, 0.f},
                    {0.f, 0.f, 0.f},   {0.5f, 0.5f, 0.f}, {1.f, 1.f, 0.f}};
    m->normals = {{nan, nan, nan}, {0.f, 0.f, 0.f}, {nan, 1.f, 0.f},
                  {0.f, 0.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 0.f}};
    m->indices = {0, 1, 2, 3, 4, 5, 2, 2, 2};
    const ecs::Entity mirror = addMesh(reg, m);
    addMesh(reg, m, {0.3f, 0.6f, 0.9f}, Transform{.translation = {0.f, 0.f, -1.f}});
    updateWorldTransforms(reg);
    const Image sky = solidImage(4, 2, {1.f, 1.f, 1.f});
    TraceOptions opt;
    opt.mirrors = {mirror};
    opt.sky = &sky;
    const GroundTruthTracer tracer(reg, opt);
    const CameraView cam =
        CameraView::lookAt({0.3f, 0.2f, 3.f}, {0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}, 1.2f, 40, 30);
    const GroundTruthImage gt = tracer.render(cam);
    int mirrorPixels = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            EXPECT_TRUE(finite(pixel(gt.color, x, y))) << x << "," << y;
            mirrorPixels += gt.mirrorMask.at(x, y)[0] > 0.5f ? 1 : 0;
        }
    EXPECT_GT(mirrorPixels, 20);
}

} // namespace
} // namespace specula
