// The glossy (GGX) ground truth's behaviour: roughness 0 is the mirror path bit for bit;
// seed-to-seed noise falls at least as 1/sqrt(samples); a seed fixes the image whatever the
// threads; tint, bounce limit and environmentOnly hold for rough mirrors as for mirrors; a
// near-mirror roughness approaches the mirror. Its energy against quadratures from the
// definitions: glossy_ground_truth_quadrature_test.cpp.
#include "engine/image_io/compare.h"
#include "engine/image_io/image_io.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "raytrace/test_scenes.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <unordered_set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <tbb/task_arena.h>

namespace specula {
namespace {

using namespace testscenes;

const std::string kRoom = SPECULA_SOURCE_DIR "/assets/room/room.gltf";
const std::string kSky = SPECULA_SOURCE_DIR "/assets/scenes/env/field.jpg";

// The bundled room with its glTF camera, its sky and its marked-up mirrors (the sphere and
// the torus: nodes whose extras hold a "specula_reflector" that is not false).
struct Room {
    ecs::Registry reg;
    LoadedScene loaded;
    Image sky;
    std::unordered_set<ecs::Entity> mirrors;
    ecs::Entity sphere = ecs::kNullEntity;

    Room() {
        loaded = loadGltf(kRoom, reg);
        sky = readImage(kSky);
        for (ecs::Entity e : loaded.entities) {
            const Extras* extras = reg.find<Extras>(e);
            if (!extras || extras->json.empty()) continue;
            const nlohmann::json j = nlohmann::json::parse(extras->json);
            if (!j.contains("specula_reflector") || j["specula_reflector"] == false) continue;
            if (reg.find<Mesh>(e)) mirrors.insert(e);
            if (const Name* n = reg.find<Name>(e); n && n->value == "sphere") sphere = e;
        }
    }

    // The scene's camera node, as the sandbox takes it.
    CameraView camera(int width, int height) const {
        for (ecs::Entity e : loaded.entities) {
            const Camera* cam = reg.find<Camera>(e);
            const Transform* t = reg.find<Transform>(e);
            if (!cam || !t) continue;
            CameraView v;
            v.view = glm::inverse(t->world);
            v.proj =
                glm::perspective(cam->yfov, float(width) / float(height), cam->znear, cam->zfar);
            v.width = width;
            v.height = height;
            return v;
        }
        ADD_FAILURE() << "the room has no camera";
        return {};
    }

    TraceOptions options() const {
        TraceOptions o;
        o.mirrors = mirrors;
        o.sky = &sky;
        return o;
    }

    // The sphere rough, every other mirror perfect.
    TraceOptions roughSphere(float roughness, int samples) const {
        TraceOptions o = options();
        const ecs::Entity s = sphere;
        o.mirrorRoughness = [s, roughness](ecs::Entity e, glm::vec2) {
            return e == s ? roughness : 0.f;
        };
        o.glossySamples = samples;
        return o;
    }
};

int countMask(const Image& mask) {
    int n = 0;
    for (float v : mask.pixels)
        n += v > 0.5f ? 1 : 0;
    return n;
}

TEST(GlossyGroundTruth, RoughnessZeroIsTheMirrorPathBitForBit) {
    Room room;
    ASSERT_EQ(room.mirrors.size(), 2u);
    ASSERT_FALSE(room.sphere.isNull());
    const CameraView cam = room.camera(160, 120);
    for (const bool environmentOnly : {false, true}) {
        TraceOptions mirror = room.options();
        mirror.environmentOnly = environmentOnly;
        mirror.mirrorTint = [&](ecs::Entity e) {
            return e == room.sphere ? glm::vec3(0.9f, 0.8f, 0.7f) : glm::vec3(1.f);
        };
        TraceOptions zero = mirror;
        zero.mirrorRoughness = [](ecs::Entity, glm::vec2) { return 0.f; };
        zero.glossySamples = 7;
        zero.seed = 12345;
        const GroundTruthImage a = GroundTruthTracer(room.reg, mirror).render(cam);
        const GroundTruthImage b = GroundTruthTracer(room.reg, zero).render(cam);
        EXPECT_GT(countMask(a.mirrorMask), 300) << "the camera sees the mirrors";
        EXPECT_EQ(a.color.pixels, b.color.pixels) << "environmentOnly " << environmentOnly;
        EXPECT_EQ(a.mirrorMask.pixels, b.mirrorMask.pixels);
        EXPECT_EQ(a.depth.pixels, b.depth.pixels);
    }
    // Rays not from a pixel too.
    const GroundTruthTracer plain(room.reg, room.options());
    TraceOptions zero = room.options();
    zero.mirrorRoughness = [](ecs::Entity, glm::vec2) { return 0.f; };
    const GroundTruthTracer zeroTracer(room.reg, zero);
    const glm::vec3 eye = cam.eye();
    for (const glm::vec3 target : {glm::vec3(-0.42f, 1.2f, 0.f), glm::vec3(0.42f, 1.25f, 0.1f)}) {
        const glm::vec3 d = glm::normalize(target - eye);
        const glm::vec3 p = plain.radiance(eye, d), q = zeroTracer.radiance(eye, d);
        EXPECT_EQ(p.r, q.r);
        EXPECT_EQ(p.g, q.g);
        EXPECT_EQ(p.b, q.b);
    }
}

// --- Noise ---------------------------------------------------------------------------------

TEST(GlossyGroundTruth, SeedToSeedNoiseFallsAtLeastAsOneOverRootSamples) {
    Room room;
    const CameraView cam = room.camera(240, 180);
    std::printf("rough sphere in the room, %dx%d, glossy noise floor (seed 1 vs 2, mirror "
                "pixels):\n",
                cam.width, cam.height);
    for (const float roughness : {0.1f, 0.35f}) {
        double psnr[3] = {};
        const int samples[3] = {64, 256, 1024};
        for (int k = 0; k < 3; ++k) {
            const GroundTruthTracer tracer(room.reg, room.roughSphere(roughness, samples[k]));
            const GroundTruthNoise noise = measureNoiseFloor(tracer, cam);
            ASSERT_TRUE(noise.stats.hasPsnr);
            EXPECT_EQ(noise.samples, samples[k]);
            EXPECT_GT(noise.stats.pixels, 300u);
            psnr[k] = noise.psnr;
            std::printf("  roughness %.2f  %4d samples  PSNR %6.2f dB  rmse %.3e  (%zu px)\n",
                        roughness, samples[k], noise.psnr, noise.stats.rmse, noise.stats.pixels);
        }
        // 16 times the samples: Monte Carlo noise would fall 16-fold in variance (+12.04 dB);
        // the scrambled (0, 2)-sequence stratifies, so it falls at least that fast (about
        // N^-1.5 where the reflection has edges: +18 dB; N^-3 at best, for smooth integrands,
        // bounded here at N^-2.5: +30 dB). A seed that did not change the samples gives inf.
        const double gain = psnr[2] - psnr[0];
        std::printf("  roughness %.2f  64 -> 1024 samples: +%.2f dB (1/sqrt(N): +12.04)\n",
                    roughness, gain);
        EXPECT_GT(gain, 12.04 - 2.5) << "roughness " << roughness;
        EXPECT_LT(gain, 12.04 * 2.5) << "roughness " << roughness;
        EXPECT_TRUE(std::isfinite(psnr[2]));
        EXPECT_LT(psnr[0], psnr[1]);
        EXPECT_LT(psnr[1], psnr[2]);
    }
}

TEST(GlossyGroundTruth, SameSeedSameImageWhateverTheThreads) {
    Room room;
    const CameraView cam = room.camera(120, 90);
    const GroundTruthTracer tracer(room.reg, room.roughSphere(0.35f, 64));
    const GroundTruthImage a = tracer.render(cam);
    // The default arena spreads rows over the workers as they come free; one thread renders
    // them in order.
    GroundTruthImage b;
    tbb::task_arena one(1);
    one.execute([&] { b = tracer.render(cam); });
    EXPECT_EQ(a.color.pixels, b.color.pixels);
    EXPECT_EQ(a.color.pixels, tracer.render(cam, 1u).color.pixels) << "the default seed is 1";
    // Another seed changes the rough pixels and only them.
    const GroundTruthImage d = tracer.render(cam, 2u);
    int changed = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const bool differs = glm::vec3(a.color.rgba(x, y)) != glm::vec3(d.color.rgba(x, y));
            changed += differs ? 1 : 0;
            if (differs) {
                EXPECT_EQ(a.mirrorMask.at(x, y)[0], 1.f) << x << "," << y;
            }
        }
    EXPECT_GT(changed, 20);
}

TEST(GlossyGroundTruth, TintAndBounceLimitApplyToRoughMirrors) {
    const Image white = solidImage(8, 4, glm::vec3(1.f));
    ecs::Registry reg;
    const ecs::Entity plane =
        addMesh(reg, quad({-100.f, 0.f, 100.f}, {200.f, 0.f, 0.f}, {0.f, 0.f, -200.f}));
    updateWorldTransforms(reg);
    TraceOptions opt;
    opt.mirrors = {plane};
    opt.sky = &white;
    opt.mirrorRoughness = [](ecs::Entity, glm::vec2) { return 0.5f; };
    opt.glossySamples = 32;
    const glm::vec3 o(0.f, 1.f, 1.f), d = glm::normalize(glm::vec3(0.f, -1.f, -1.f));
    const glm::vec3 plain = GroundTruthTracer(reg, opt).radiance(o, d);
    EXPECT_GT(plain.r, 0.5f);
    EXPECT_LT(plain.r, 1.f);
    opt.mirrorTint = [](ecs::Entity) { return glm::vec3(1.f, 0.5f, 0.25f); };
    const glm::vec3 tinted = GroundTruthTracer(reg, opt).radiance(o, d);
    EXPECT_FLOAT_EQ(tinted.r, plain.r);
    EXPECT_FLOAT_EQ(tinted.g, 0.5f * plain.r);
    EXPECT_FLOAT_EQ(tinted.b, 0.25f * plain.r);
    opt.maxBounces = 0;
    EXPECT_EQ(GroundTruthTracer(reg, opt).radiance(o, d), glm::vec3(0.f));
}

TEST(GlossyGroundTruth, NearMirrorRoughnessApproachesTheMirror) {
    Room room;
    const CameraView cam = room.camera(160, 120);
    const GroundTruthImage mirror = GroundTruthTracer(room.reg, room.options()).render(cam);
    double last = 0.0;
    for (const float roughness : {0.2f, 0.05f, 0.01f}) {
        const GroundTruthImage rough =
            GroundTruthTracer(room.reg, room.roughSphere(roughness, 64)).render(cam);
        const ImageStats s = compareImages(mirror.color, rough.color, &mirror.mirrorMask);
        std::printf("roughness %.2f against the mirror: PSNR %s dB\n", roughness,
                    formatPsnr(s.psnr).c_str());
        ASSERT_TRUE(s.hasPsnr);
        EXPECT_GT(s.psnr, last) << roughness;
        last = s.psnr;
    }
    EXPECT_GT(last, 40.0);
}

// Reflected rays of a rough mirror see the environment only, as a mirror's do: with the wall
// mirror B marked invisible, the rough floor sees what it sees when B is not there at all.
TEST(GlossyGroundTruth, EnvironmentOnlyHoldsForRoughSamples) {
    const Image sky = solidImage(8, 4, {0.f, 0.f, 1.f});
    auto build = [](ecs::Registry& reg, bool withB, ecs::Entity& a, ecs::Entity& b) {
        a = addMesh(reg, quad({-5.f, 0.f, 5.f}, {10.f, 0.f, 0.f}, {0.f, 0.f, -10.f}));
        if (withB) b = addMesh(reg, quad({2.f, 1.f, 1.f}, {0.f, 0.f, -2.f}, {0.f, 2.f, 0.f}));
        addMesh(reg, quad({4.f, 0.f, 2.f}, {0.f, 8.f, 0.f}, {0.f, 0.f, -4.f}), {1.f, 0.f, 0.f});
        updateWorldTransforms(reg);
    };
    ecs::Registry withB, withoutB;
    ecs::Entity a1, b1, a2, b2;
    build(withB, true, a1, b1);
    build(withoutB, false, a2, b2);
    auto options = [&](std::unordered_set<ecs::Entity> mirrors, bool environmentOnly) {
        TraceOptions o;
        o.mirrors = std::move(mirrors);
        o.sky = &sky;
        o.environmentOnly = environmentOnly;
        o.mirrorRoughness = [](ecs::Entity, glm::vec2) { return 0.3f; };
        o.glossySamples = 64;
        return o;
    };
    const glm::vec3 o(-2.f, 2.f, 0.f), d = glm::normalize(glm::vec3(1.f, -1.f, 0.f));
    const glm::vec3 invisible = GroundTruthTracer(withB, options({a1, b1}, true)).radiance(o, d);
    const glm::vec3 absent = GroundTruthTracer(withoutB, options({a2}, true)).radiance(o, d);
    const glm::vec3 visible = GroundTruthTracer(withB, options({a1, b1}, false)).radiance(o, d);
    EXPECT_NEAR(invisible.r, absent.r, 1e-6f);
    EXPECT_NEAR(invisible.b, absent.b, 1e-6f);
    EXPECT_GT(invisible.r, 0.1f) << "the red wall through B";
    EXPECT_LT(visible.r, invisible.r - 0.05f) << "B hides the red wall when visible";
}

} // namespace
} // namespace specula
