// The glossy (GGX) ground truth: roughness 0 is the mirror path bit for bit; a white
// furnace returns the GGX directional albedo (F = 1, Smith height-correlated) and a graded
// sky the integral of the lobe, both computed here by quadrature from the definitions;
// seed-to-seed noise falls at least as 1/sqrt(samples); a seed fixes the image whatever the
// threads; tint, bounce limit and environmentOnly hold for rough mirrors as for mirrors.
#include "engine/image_io/compare.h"
#include "engine/image_io/image_io.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/components.h"
#include "engine/scene/gltf_loader.h"
#include "raytrace/test_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <unordered_set>

#include <glm/gtc/constants.hpp>
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

// --- White furnace -------------------------------------------------------------------------
//
// Under a sky of radiance 1 everywhere, a rough reflector with F = 1 returns its directional
// albedo E(v) = integral over n.l > 0 of D(h) G2(v, l) / (4 n.v) dl. Computed here by
// midpoint quadrature in a frame with n = +Z, written from the definitions and not from the
// tracer's sampling: D is GGX, G2 = 1 / (1 + Lambda(v) + Lambda(l)).

double ggxD(double cosH, double alpha) {
    const double a2 = alpha * alpha;
    const double k = cosH * cosH * (a2 - 1.0) + 1.0;
    return a2 / (glm::pi<double>() * k * k);
}

double ggxLambda(double cosTheta, double alpha) {
    const double c2 = cosTheta * cosTheta;
    const double tan2 = (1.0 - c2) / c2;
    return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// Over half vectors h: dl = 4 (v.h) dh, and with xi = t / (1 + t), t = tan^2(theta_h) /
// alpha^2, D(h) cos(theta_h) dh = dxi dphi / (2 pi), so
//   E = integral over [0,1) x [0,2pi) of G2 (v.h) / ((n.v) (n.h)) [v.h > 0, n.l > 0]
//       dxi dphi / (2 pi).
// GGX has long tails (a share ~alpha^2 of the normals lies beyond 45 degrees, where l falls
// below the horizon), so xi = 1 - exp(-s) is integrated over s in [0, 40]: the tail gets
// as many nodes as the core. The integrand is bounded and goes to 0 continuously at the
// horizon (G2 -> 0).
// `sky(l)`: the radiance arriving from l (local frame); the albedo takes 1.
using LocalSky = std::function<double(const glm::dvec3&)>;

double reflectedOverHalfVectors(double alpha, double cosV, int nS, int nPhi, const LocalSky& sky) {
    const glm::dvec3 v(std::sqrt(1.0 - cosV * cosV), 0.0, cosV);
    const double lambdaV = ggxLambda(cosV, alpha);
    constexpr double kS = 40.0;
    double sum = 0.0;
    for (int i = 0; i < nS; ++i) {
        // Midpoint in s for the integrand, the exact mass exp(-s) ds of each cell.
        const double s = kS * (i + 0.5) / nS;
        const double oneMinusXi = std::exp(-s);
        const double mass = std::exp(-kS * i / nS) - std::exp(-kS * (i + 1) / nS);
        const double tanTheta = alpha * std::sqrt((1.0 - oneMinusXi) / oneMinusXi);
        const double cosH = 1.0 / std::sqrt(1.0 + tanTheta * tanTheta);
        const double sinH = tanTheta * cosH;
        double ring = 0.0;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = glm::two_pi<double>() * (j + 0.5) / nPhi;
            const glm::dvec3 h(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
            const double vh = glm::dot(v, h);
            if (vh <= 0.0) continue;
            const glm::dvec3 l = 2.0 * vh * h - v;
            if (l.z <= 0.0) continue;
            const double g2 = 1.0 / (1.0 + lambdaV + ggxLambda(l.z, alpha));
            ring += g2 * vh / (cosV * cosH) * (sky ? sky(l) : 1.0);
        }
        sum += ring * mass;
    }
    return sum / nPhi;
}

double albedoOverHalfVectors(double alpha, double cosV, int nS, int nPhi) {
    return reflectedOverHalfVectors(alpha, cosV, nS, nPhi, {});
}

// Directly over light directions, in polar coordinates about the mirror direction r with a
// polar angle graded towards r (beta = pi s^3): a second route, for the wider lobes.
double albedoOverLightDirections(double alpha, double cosV, int nS, int nPhi) {
    const glm::dvec3 v(std::sqrt(1.0 - cosV * cosV), 0.0, cosV);
    const glm::dvec3 r(-v.x, 0.0, v.z);
    const glm::dvec3 e1(r.z, 0.0, -r.x), e2(0.0, 1.0, 0.0);
    const double lambdaV = ggxLambda(cosV, alpha);
    double sum = 0.0;
    for (int i = 0; i < nS; ++i) {
        const double s = (i + 0.5) / nS;
        const double beta = glm::pi<double>() * s * s * s;
        const double dBeta = 3.0 * glm::pi<double>() * s * s / nS;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = glm::two_pi<double>() * (j + 0.5) / nPhi;
            const glm::dvec3 l =
                std::cos(beta) * r + std::sin(beta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
            if (l.z <= 0.0) continue;
            const glm::dvec3 h = glm::normalize(v + l);
            const double g2 = 1.0 / (1.0 + lambdaV + ggxLambda(l.z, alpha));
            const double f = ggxD(h.z, alpha) * g2 / (4.0 * cosV); // f (n.l), F = 1
            sum += f * std::sin(beta) * dBeta * (glm::two_pi<double>() / nPhi);
        }
    }
    return sum;
}

TEST(GlossyGroundTruth, AlbedoQuadraturesAgree) {
    // The two routes to the reference agree, and a near-mirror keeps all its energy.
    for (const double roughness : {0.35, 0.6, 1.0})
        for (const double cosV : {1.0, 0.5, 0.2}) {
            const double alpha = roughness * roughness;
            const double a = albedoOverHalfVectors(alpha, cosV, 2048, 1024);
            const double b = albedoOverLightDirections(alpha, cosV, 2048, 1024);
            EXPECT_NEAR(a, b, 2e-4) << "roughness " << roughness << " cos " << cosV;
            EXPECT_LE(a, 1.0);
        }
    EXPECT_NEAR(albedoOverHalfVectors(1e-6, 0.7, 512, 256), 1.0, 1e-5);
}

TEST(GlossyGroundTruth, WhiteFurnaceReturnsTheGgxAlbedo) {
    // A rough mirror plane y = 0 under a white sky, nothing else.
    const Image white = solidImage(8, 4, glm::vec3(1.f));
    ecs::Registry reg;
    const ecs::Entity plane =
        addMesh(reg, quad({-100.f, 0.f, 100.f}, {200.f, 0.f, 0.f}, {0.f, 0.f, -200.f}));
    updateWorldTransforms(reg);
    constexpr int kSamples = 256, kGrid = 16, kRays = kGrid * kGrid;
    std::printf("roughness  view   E(quadrature)  mean(estimator)  error      sd/sqrt(P)  "
                "bound\n");
    for (const float roughness : {0.1f, 0.35f, 0.6f, 1.f}) {
        TraceOptions opt;
        opt.mirrors = {plane};
        opt.sky = &white;
        opt.mirrorRoughness = [roughness](ecs::Entity, glm::vec2) { return roughness; };
        opt.glossySamples = kSamples;
        const GroundTruthTracer tracer(reg, opt);
        for (const double viewDeg : {0.0, 45.0, 70.0, 85.0}) {
            const double alpha = double(roughness) * roughness;
            const double cosV = std::cos(glm::radians(viewDeg));
            const double reference = albedoOverHalfVectors(alpha, cosV, 4096, 1024);
            // One estimate per ray, each ray its own randomisation (a different hit point).
            const glm::vec3 v(float(std::sin(glm::radians(viewDeg))), float(cosV), 0.f);
            double sum = 0.0, sum2 = 0.0;
            for (int i = 0; i < kRays; ++i) {
                const glm::vec3 p(-1.f + 2.f * float(i % kGrid) / kGrid, 0.f,
                                  -1.f + 2.f * float(i / kGrid) / kGrid);
                const glm::vec3 c = tracer.radiance(p + v, -v);
                ASSERT_EQ(c.r, c.g);
                ASSERT_EQ(c.r, c.b);
                ASSERT_GE(c.r, 0.f);
                ASSERT_LE(c.r, 1.f + 1e-6f);
                sum += c.r;
                sum2 += double(c.r) * c.r;
            }
            const double mean = sum / kRays;
            const double sd = std::sqrt(std::max(0.0, sum2 / kRays - mean * mean));
            // Each sample's weight G2 / G1 lies in [0, 1] with mean E, so its variance is at
            // most E (1 - E); Owen-scrambled (0, 2)-nets have at most twice the Monte Carlo
            // variance (Owen 1997), and the kRays estimates are independent: the mean's
            // standard deviation is at most sqrt(2 E (1 - E) / (N P)). Four of those, plus
            // 2e-5 for float sums and the quadrature.
            const double bound =
                4.0 * std::sqrt(2.0 * reference * (1.0 - reference) / (double(kSamples) * kRays)) +
                2e-5;
            std::printf("%9.2f  %4.0f   %13.6f  %15.6f  %+.2e  %.2e    %.2e\n", roughness, viewDeg,
                        reference, mean, mean - reference, sd / std::sqrt(kRays), bound);
            EXPECT_NEAR(mean, reference, bound)
                << "roughness " << roughness << " view " << viewDeg << " deg";
            EXPECT_LE(mean, 1.0 + 1e-6);
        }
    }
}

// The furnace checks the weights' integral; a sky that varies checks where the samples go:
// its gradient the lobe's lean away from the mirror direction, its curvature the lobe's
// width. L(d) = 1 + 0.5 d.x + 0.5 d.z^2 in the scene (the plane's normal is +Y, the view in
// the XY plane), tabulated finely enough that bilinear lookup adds < 1e-5.
TEST(GlossyGroundTruth, GradedSkyMatchesQuadratureOfTheLobe) {
    auto radianceOf = [](glm::dvec3 d) { return 1.0 + 0.5 * d.x + 0.5 * d.z * d.z; };
    Image sky(2048, 1024, 3);
    for (int j = 0; j < sky.height; ++j)
        for (int i = 0; i < sky.width; ++i) {
            // The inverse of equirectUv at the texel centre.
            const double theta = glm::pi<double>() * (j + 0.5) / sky.height;
            const double phi = glm::two_pi<double>() * ((i + 0.5) / sky.width - 0.5);
            const glm::dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                               -std::sin(theta) * std::cos(phi));
            const float value = float(radianceOf(d));
            sky.at(i, j)[0] = sky.at(i, j)[1] = sky.at(i, j)[2] = value;
        }
    ecs::Registry reg;
    const ecs::Entity plane =
        addMesh(reg, quad({-100.f, 0.f, 100.f}, {200.f, 0.f, 0.f}, {0.f, 0.f, -200.f}));
    updateWorldTransforms(reg);
    {
        TraceOptions skyOnly;
        skyOnly.sky = &sky;
        const GroundTruthTracer bare(reg, skyOnly);
        for (const glm::vec3 d : {glm::vec3(0.3f, 0.8f, -0.5f), glm::vec3(-0.9f, 0.1f, 0.4f)})
            ASSERT_NEAR(bare.sky(d).r, radianceOf(glm::normalize(glm::dvec3(d))), 1e-5);
    }
    // Local frame of the quadrature (n = +Z, v in XZ) to the scene's: (x, y, z) -> (x, z, y).
    const LocalSky local = [&](const glm::dvec3& l) { return radianceOf({l.x, l.z, l.y}); };
    constexpr int kSamples = 256, kGrid = 16, kRays = kGrid * kGrid;
    std::printf("graded sky: roughness  view   reference  estimator  error      bound\n");
    for (const float roughness : {0.2f, 0.5f, 0.8f}) {
        TraceOptions opt;
        opt.mirrors = {plane};
        opt.sky = &sky;
        opt.mirrorRoughness = [roughness](ecs::Entity, glm::vec2) { return roughness; };
        opt.glossySamples = kSamples;
        const GroundTruthTracer tracer(reg, opt);
        for (const double viewDeg : {30.0, 75.0}) {
            const double cosV = std::cos(glm::radians(viewDeg));
            const double reference =
                reflectedOverHalfVectors(double(roughness) * roughness, cosV, 2048, 1024, local);
            const glm::vec3 v(float(std::sin(glm::radians(viewDeg))), float(cosV), 0.f);
            double sum = 0.0, sum2 = 0.0;
            for (int i = 0; i < kRays; ++i) {
                const glm::vec3 p(-1.f + 2.f * float(i % kGrid) / kGrid, 0.f,
                                  -1.f + 2.f * float(i / kGrid) / kGrid);
                const double c = tracer.radiance(p + v, -v).r;
                sum += c;
                sum2 += c * c;
            }
            const double mean = sum / kRays;
            // The kRays estimates are independent randomisations: their spread measures the
            // estimator's (a general bound, as in the furnace, would be 100x looser than the
            // effects it should catch). Five standard deviations of the mean, plus 1e-4 for
            // the sky's bilinear lookup and float sums.
            const double sdMean =
                std::sqrt(std::max(0.0, sum2 / kRays - mean * mean) / (kRays - 1));
            const double bound = 5.0 * sdMean + 1e-4;
            std::printf("            %9.2f  %4.0f   %9.6f  %9.6f  %+.2e  %.2e\n", roughness,
                        viewDeg, reference, mean, mean - reference, bound);
            EXPECT_NEAR(mean, reference, bound)
                << "roughness " << roughness << " view " << viewDeg << " deg";
        }
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
