#include "engine/raytrace/embree_scene.h"

#include "raytrace/test_scenes.h"

#include <limits>
#include <random>

#include <gtest/gtest.h>

namespace specula {
namespace {

using namespace testscenes;

// Slab test: entry distance of the ray into the box, or nullopt.
std::optional<float> slabDistance(glm::vec3 o, glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
    float t0 = 0.f, t1 = std::numeric_limits<float>::infinity();
    for (int a = 0; a < 3; ++a) {
        const float inv = 1.f / d[a];
        float ta = (lo[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (t0 > t1) return std::nullopt;
    return t0;
}

TEST(EmbreeScene, EmptyRegistryHitsNothing) {
    ecs::Registry reg;
    const EmbreeScene scene(reg);
    EXPECT_TRUE(scene.empty());
    EXPECT_FALSE(scene.intersect({0, 0, 0}, {0, 0, -1}).has_value());
}

TEST(EmbreeScene, UnitCubeHitDistancesMatchClosedForm) {
    ecs::Registry reg;
    const ecs::Entity e = addMesh(reg, cube());
    updateWorldTransforms(reg);
    const EmbreeScene scene(reg);
    ASSERT_EQ(scene.geometryCount(), 1u);

    // Axis rays with known answers.
    auto h = scene.intersect({0.f, 0.f, 3.f}, {0.f, 0.f, -1.f});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 2.5f, 1e-5f);
    EXPECT_EQ(h->entity, e);
    EXPECT_NEAR(h->geometricNormal.z, 1.f, 1e-6f);
    EXPECT_NEAR(h->normal.z, 1.f, 1e-6f);
    h = scene.intersect({2.f, 0.1f, 0.2f}, {-2.f, 0.f, 0.f}); // t in units of |dir|
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 0.75f, 1e-5f);
    h = scene.intersect({0.f, 0.f, 0.f}, {0.f, 1.f, 0.f}); // from inside
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 0.5f, 1e-5f);
    EXPECT_FALSE(scene.intersect({0.f, 2.f, 0.f}, {0.f, 1.f, 0.f}));
    EXPECT_FALSE(scene.intersect({0.f, 2.f, 0.f}, {1.f, 0.f, 0.f}));

    // Random rays from a surrounding sphere towards points inside the cube.
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 200; ++i) {
        glm::vec3 o(u(rng), u(rng), u(rng));
        if (glm::length(o) < 0.1f) continue;
        o = 4.f * glm::normalize(o);
        const glm::vec3 target = 0.45f * glm::vec3(u(rng), u(rng), u(rng));
        const glm::vec3 d = glm::normalize(target - o);
        const auto expected = slabDistance(o, d, glm::vec3(-0.5f), glm::vec3(0.5f));
        ASSERT_TRUE(expected);
        const auto hit = scene.intersect(o, d);
        ASSERT_TRUE(hit) << i;
        EXPECT_NEAR(hit->t, *expected, 2e-5f) << i;
        EXPECT_NEAR(glm::length(hit->position - (o + *expected * d)), 0.f, 1e-4f);
        // The normal is the face the point lies on: its largest coordinate.
        const glm::vec3 p = hit->position, a = glm::abs(p);
        const int axis = a.x > a.y && a.x > a.z ? 0 : (a.y > a.z ? 1 : 2);
        EXPECT_NEAR(hit->geometricNormal[axis], p[axis] > 0.f ? 1.f : -1.f, 1e-5f) << i;
    }
}

TEST(EmbreeScene, TransformedCubeUsesWorldSpace) {
    ecs::Registry reg;
    Transform xf;
    xf.translation = {1.f, 0.f, 0.f};
    xf.scale = {2.f, 1.f, 1.f};
    xf.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0.f, 1.f, 0.f));
    addMesh(reg, cube(), glm::vec3(1.f), xf);
    updateWorldTransforms(reg);
    const EmbreeScene scene(reg);
    // Rotated 90 degrees about Y, the long (x) side lies along z: box [0.5,1.5]x[-.5,.5]x[-1,1].
    const auto h = scene.intersect({1.f, 0.f, 5.f}, {0.f, 0.f, -1.f});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->t, 4.f, 1e-5f);
    EXPECT_NEAR(h->normal.z, 1.f, 1e-5f);
    const auto side = scene.intersect({-3.f, 0.2f, 0.3f}, {1.f, 0.f, 0.f});
    ASSERT_TRUE(side);
    EXPECT_NEAR(side->t, 3.5f, 1e-5f);
    EXPECT_NEAR(side->normal.x, -1.f, 1e-5f);
}

TEST(EmbreeScene, IncludeAndAcceptFilters) {
    ecs::Registry reg;
    const ecs::Entity nearQuad =
        addMesh(reg, quad({-1.f, -1.f, 1.f}, {2.f, 0.f, 0.f}, {0.f, 2.f, 0.f}));
    const ecs::Entity farQuad =
        addMesh(reg, quad({-1.f, -1.f, -1.f}, {2.f, 0.f, 0.f}, {0.f, 2.f, 0.f}));
    updateWorldTransforms(reg);
    const EmbreeScene all(reg);
    const EmbreeScene onlyFar(reg, [&](ecs::Entity e) { return e == farQuad; });
    const glm::vec3 o(0.f, 0.f, 5.f), d(0.f, 0.f, -1.f);
    EXPECT_EQ(all.intersect(o, d)->entity, nearQuad);
    EXPECT_EQ(onlyFar.intersect(o, d)->entity, farQuad);
    const EmbreeScene::Filter rejectNear = [&](ecs::Entity e) { return e != nearQuad; };
    const auto h = all.intersect(o, d, 0.f, std::numeric_limits<float>::infinity(), &rejectNear);
    ASSERT_TRUE(h);
    EXPECT_EQ(h->entity, farQuad);
    EXPECT_NEAR(h->t, 6.f, 1e-5f);
    const EmbreeScene::Filter none = [](ecs::Entity) { return false; };
    EXPECT_FALSE(all.intersect(o, d, 0.f, std::numeric_limits<float>::infinity(), &none));
}

TEST(EmbreeScene, AlbedoIsFactorTimesBilinearTexture) {
    auto tex = std::make_shared<Image>(2, 2, 4);
    const glm::vec4 texels[4] = {
        {1.f, 0.f, 0.f, 1.f}, {0.f, 1.f, 0.f, 1.f}, {0.f, 0.f, 1.f, 1.f}, {1.f, 1.f, 1.f, 1.f}};
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 4; ++c)
            tex->at(i % 2, i / 2)[c] = texels[i][c];
    ecs::Registry reg;
    addMesh(reg, quad({0.f, 0.f, 0.f}, {4.f, 0.f, 0.f}, {0.f, 4.f, 0.f}), {0.5f, 1.f, 1.f}, {},
            tex);
    updateWorldTransforms(reg);
    const EmbreeScene scene(reg);
    // uv (0.25, 0.25) is the centre of texel (0, 0); (0.5, 0.25) halfway to texel (1, 0).
    auto h = scene.intersect({1.f, 1.f, 1.f}, {0.f, 0.f, -1.f});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->uv.x, 0.25f, 1e-6f);
    EXPECT_NEAR(h->uv.y, 0.25f, 1e-6f);
    EXPECT_NEAR(h->albedo.r, 0.5f, 1e-6f);
    EXPECT_NEAR(h->albedo.g, 0.f, 1e-6f);
    h = scene.intersect({2.f, 1.f, 1.f}, {0.f, 0.f, -1.f});
    ASSERT_TRUE(h);
    EXPECT_NEAR(h->albedo.r, 0.25f, 1e-6f);
    EXPECT_NEAR(h->albedo.g, 0.5f, 1e-6f);
    EXPECT_NEAR(h->albedo.b, 0.f, 1e-6f);
}

TEST(EmbreeScene, DegenerateTrianglesAndBadNormalsStayFinite) {
    auto m = std::make_shared<MeshData>();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    m->positions = {{-1.f, -1.f, 0.f}, {1.f, -1.f, 0.f}, {1.f, 1.f, 0.f}, // valid
                    {-1.f, 0.f, 0.f},  {0.f, 0.f, 0.f},  {1.f, 0.f, 0.f}, // collinear
                    {0.f, 0.f, 0.f}};
    m->normals = {{nan, nan, nan}, {nan, 0.f, 0.f}, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f},
                  {0.f, 0.f, 1.f}, {0.f, 0.f, 1.f}, {0.f, 0.f, 0.f}};
    m->indices = {0, 1, 2, 3, 4, 5, 6, 6, 6, 0, 1, 99 /* out of range */, 7};
    ecs::Registry reg;
    addMesh(reg, m);
    auto zeroArea = std::make_shared<MeshData>();
    zeroArea->positions = {{0.f, 0.f, 0.5f}, {0.f, 0.f, 0.5f}, {0.f, 0.f, 0.5f}};
    zeroArea->indices = {0, 1, 2};
    addMesh(reg, zeroArea);
    updateWorldTransforms(reg);
    const EmbreeScene scene(reg);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 o(u(rng), u(rng), 2.f);
        const glm::vec3 target =
            i < 20 ? glm::vec3(u(rng), 0.f, 0.f) : glm::vec3(u(rng), u(rng), 0.f);
        const auto h = scene.intersect(o, target - o);
        if (!h) continue;
        ++hits;
        EXPECT_TRUE(finite(h->position) && finite(h->normal) && finite(h->geometricNormal) &&
                    finite(h->albedo))
            << i;
        EXPECT_TRUE(std::isfinite(h->uv.x) && std::isfinite(h->t));
        EXPECT_NEAR(glm::length(h->normal), 1.f, 1e-5f);
        // Unusable normals fall back to the geometric one.
        EXPECT_NEAR(h->normal.z, 1.f, 1e-5f);
    }
    EXPECT_GT(hits, 50);
}

} // namespace
} // namespace specula
