// A flavour is one folder: the constant-colour flavour (tests/probe/constant_flavour/, no
// file outside tests/ edited for it) registers with ReflectionProbeSystem through
// addFlavour() and draws. Checked against independent references: the Embree tracer's
// mirror mask says which pixels are reflectors, the flavour's C++ twin says their colour.
// Links components and engine only: no sandbox code.
#include "constant_flavour/constant_flavour.h"

#include "assetcooker/lib/scene/probe_setup.h"
#include "assetcooker/lib/scene/reflector_pixels.h"
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/system/reflection_probe_system.h"
#include "engine/context/context.h"
#include "engine/core/error.h"
#include "engine/gpu/render_target.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/render/scene_renderer.h"
#include "engine/scene/mesh_bounds.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <set>

using namespace specula;
using test::ConstantProbe;
using test::ConstantStore;

namespace {

constexpr int kWidth = 160, kHeight = 120;
const std::string kRoom = std::string(SPECULA_SOURCE_DIR) + "/assets/room/room.gltf";

class ConstantFlavour : public test::ScratchDirTest {
protected:
    ConstantFlavour() : ScratchDirTest("specula-constant-flavour") {}

    void SetUp() override {
        ScratchDirTest::SetUp();
        context_ = gpu::GlContext::createHeadless();
        renderer_ = std::make_unique<SceneRenderer>();
        target_ = std::make_unique<gpu::RenderTarget>(kWidth, kHeight);
        scene_ = std::make_unique<ProbeScene>(kRoom, "");
        manifest_ = (root_ / "constant" / "manifest.json").string();
        test::writeConstantProbe({kColour}, (root_ / "constant").string());
        // A view of the reflectors from 3 m in front and above.
        Aabb box;
        for (const ReflectorMarkup& r : scene_->markup.reflectors)
            for (ecs::Entity mesh : r.meshes)
                box.extend(meshWorldBoundsConservative(scene_->registry, mesh));
        const glm::vec3 centre = box.centre();
        camera_ = CameraView::lookAt(centre + glm::vec3(0.f, 1.2f, 3.f), centre, glm::vec3(0, 1, 0),
                                     glm::radians(50.f), kWidth, kHeight);
        // Reflector pixels away from their silhouette, by the ray tracer.
        TraceOptions o;
        o.mirrors = scene_->markup.mirrorEntities;
        o.maxBounces = 1;
        const Image mask =
            GroundTruthTracer(scene_->registry, std::move(o)).render(camera_).mirrorMask;
        interior_ = Image(kWidth, kHeight, 1);
        outside_ = Image(kWidth, kHeight, 1);
        for (int y = 1; y + 1 < kHeight; ++y)
            for (int x = 1; x + 1 < kWidth; ++x) {
                float lo = 1.f, hi = 0.f;
                for (auto [dx, dy] : {std::pair{0, 0}, {1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                    lo = std::min(lo, mask.at(x + dx, y + dy)[0]);
                    hi = std::max(hi, mask.at(x + dx, y + dy)[0]);
                }
                interior_.at(x, y)[0] = lo;
                outside_.at(x, y)[0] = 1.f - hi;
            }
    }

    ecs::Entity attach(const ConstantProbe& settings) {
        probe_ = attachProbeComponents(scene_->registry, scene_->markup, ReflectionProbe{manifest_},
                                       probe_);
        scene_->registry.emplace<ConstantProbe>(probe_, settings);
        return probe_;
    }

    Image draw(ReflectionProbeSystem& system) {
        renderer_->sync(scene_->registry);
        system.sync(scene_->registry);
        renderer_->render(camera_, *target_,
                          [&](ecs::Entity e) { return scene_->registry.has<Reflector>(e); });
        system.render(scene_->registry, camera_, *renderer_, *target_);
        return target_->readback();
    }

    // Pixels of `mask` whose colour is `want` (to float rounding), and how many there are.
    static std::pair<long, long> matching(const Image& img, const Image& mask, glm::vec3 want) {
        long hit = 0, n = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                if (mask.at(x, y)[0] < 0.5f) continue;
                ++n;
                if (glm::length(glm::vec3(img.rgba(x, y)) - want) < 1e-5f) ++hit;
            }
        return {hit, n};
    }

    static constexpr glm::vec3 kColour{0.123f, 0.456f, 0.789f};
    std::unique_ptr<gpu::GlContext> context_;
    std::unique_ptr<ProbeScene> scene_;
    std::string manifest_;
    ecs::Entity probe_ = ecs::kNullEntity;
    CameraView camera_;
    Image interior_, outside_;
    std::unique_ptr<SceneRenderer> renderer_; // after the context: destroyed before it
    std::unique_ptr<gpu::RenderTarget> target_;
};

} // namespace

TEST_F(ConstantFlavour, RegistersDrawsTheTwinsColourOnReflectorPixelsOnly) {
    ReflectionProbeSystem system;
    system.addFlavour(std::make_unique<ConstantStore>());
    const ecs::Entity probe = attach(ConstantProbe{});
    const Image img = draw(system);
    const glsl::ConstantParams* params = system.store<ConstantStore>()->params(probe);
    ASSERT_NE(params, nullptr);
    const glm::vec3 twin = test::constantTwin(*params);
    EXPECT_EQ(twin, kColour);
    const auto [inside, insideN] = matching(img, interior_, twin);
    const auto [outside, outsideN] = matching(img, outside_, twin);
    std::printf("constant flavour: %ld of %ld reflector px hold the twin's colour, %ld of %ld "
                "other px\n",
                inside, insideN, outside, outsideN);
    ASSERT_GT(insideN, 200) << "the camera must see the reflectors";
    EXPECT_EQ(inside, insideN);
    EXPECT_EQ(outside, 0);
    // One variant per kind of reflector in view: mirrors, and Fresnel ones (the room's
    // sphere has F0 = 1, which Schlick leaves at exactly the twin's colour).
    std::set<std::string> want;
    for (const ReflectorMarkup& r : scene_->markup.reflectors)
        want.insert(r.f0 >= 0.f ? "constant+fresnel" : "constant");
    const auto& drawn = system.stats().permutations;
    EXPECT_EQ(std::set<std::string>(drawn.begin(), drawn.end()), want);
    EXPECT_GT(system.stats().reflectorsDrawn, 0u);
}

TEST_F(ConstantFlavour, SettingsEditReachesTheShaderThroughTheBlockOnly) {
    ReflectionProbeSystem system;
    system.addFlavour(std::make_unique<ConstantStore>());
    const ecs::Entity probe = attach(ConstantProbe{});
    draw(system);
    const std::size_t uploads = system.stats().textureUploads;
    const std::size_t blocks = system.stats().parameterUploads;
    scene_->registry.get<ConstantProbe>(probe).gain = 0.5f;
    const Image img = draw(system);
    EXPECT_EQ(system.stats().parameterUploads, blocks + 1);
    EXPECT_EQ(system.stats().textureUploads, uploads);
    const auto [inside, n] = matching(img, interior_, 0.5f * kColour);
    EXPECT_EQ(inside, n);
    draw(system); // nothing edited: nothing uploaded
    EXPECT_EQ(system.stats().parameterUploads, blocks + 1);
}

TEST_F(ConstantFlavour, AnUnregisteredFlavourIsRefusedNamingTheKnownOnes) {
    ReflectionProbeSystem system; // the built-in flavours only
    attach(ConstantProbe{});
    try {
        draw(system);
        FAIL() << "expected the constant flavour to be unknown";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), manifest_);
        EXPECT_EQ(e.field(), "flavour");
        EXPECT_NE(std::string(e.what()).find("distance, distance-level, lightfield"),
                  std::string::npos)
            << e.what();
    }
}

TEST_F(ConstantFlavour, AnotherFlavoursSettingsOnTheProbeAreRefused) {
    ReflectionProbeSystem system;
    system.addFlavour(std::make_unique<ConstantStore>());
    const ecs::Entity probe = attach(ConstantProbe{});
    scene_->registry.emplace<DistanceProbe>(probe, DistanceProbe{});
    try {
        draw(system);
        FAIL() << "expected DistanceProbe settings on a constant probe to be refused";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), manifest_);
        EXPECT_EQ(e.field(), "flavour");
        EXPECT_NE(std::string(e.what()).find("DistanceProbe"), std::string::npos) << e.what();
    }
    EXPECT_THROW(system.addFlavour(std::make_unique<ConstantStore>()), Error)
        << "a flavour registers once";
}

TEST_F(ConstantFlavour, FineDerivativesOfTheReflectedDirectionMatchTheQuadTwin) {
    // The shader's dFdxFine / dFdyFine of the reflected direction (OUTPUT 3 and 4) against
    // ReflectorQuadPixel's, whose quad partners are shaded on the pixel's own triangle plane
    // as the GPU's helper invocations are: what a twin of a MIP level or a footprint needs.
    // The naive twin (the neighbouring pixel's own hit) is measured beside it: it differs
    // wherever the partner lies on another triangle or off the reflector.
    ReflectionProbeSystem system;
    system.addFlavour(std::make_unique<ConstantStore>());
    attach(ConstantProbe{});
    Image derivative[2];
    for (int k = 0; k < 2; ++k) {
        renderer_->sync(scene_->registry);
        system.sync(scene_->registry);
        renderer_->render(camera_, *target_,
                          [&](ecs::Entity e) { return scene_->registry.has<Reflector>(e); });
        system.render(scene_->registry, camera_, *renderer_, *target_, 3 + k);
        derivative[k] = target_->readback();
    }
    TraceOptions o;
    o.mirrors = scene_->markup.mirrorEntities;
    o.maxBounces = 1;
    const GroundTruthTracer tracer(scene_->registry, std::move(o));
    Image mask = tracer.render(camera_).mirrorMask;
    const std::vector<ReflectorQuadPixel> quads =
        reflectorQuadPixels(scene_->registry, tracer, camera_, mask);
    const std::vector<ReflectorPixel> pixels = reflectorPixels(tracer, camera_, mask);
    ASSERT_EQ(quads.size(), pixels.size());
    std::map<std::pair<int, int>, glm::vec3> lhatAt;
    for (const ReflectorPixel& p : pixels)
        lhatAt[{p.x, p.y}] = p.lhat;
    const auto lhat = [](const ReflectorPixel& p) { return p.lhat; };
    // Counts over every reflector pixel of the tracer's mask [0] and over those away from
    // its silhouette [1] (where raster and tracer coverage agree for certain).
    long n[2] = {}, close[2] = {}, naiveClose = 0, naiveN = 0;
    double worst[2] = {}, scale = 0;
    for (const ReflectorQuadPixel& q : quads) {
        const bool interior = interior_.at(q.pixel.x, q.pixel.y)[0] > 0.5f;
        for (int k = 0; k < 2; ++k) {
            const glm::vec3 gpu(derivative[k].rgba(q.pixel.x, q.pixel.y));
            const glm::vec3 twin = k == 0 ? q.dFdxFine(lhat) : q.dFdyFine(lhat);
            const double err = glm::length(gpu - twin);
            const bool ok = err < 1e-3 + 1e-2 * glm::length(gpu);
            for (int m = 0; m < (interior ? 2 : 1); ++m) {
                ++n[m];
                close[m] += ok;
                worst[m] = std::max(worst[m], err);
            }
            scale += glm::length(twin);
            // The naive twin: the partner pixel's own primary hit, where it has one.
            const ReflectorPixel& partner = k == 0 ? q.acrossX : q.acrossY;
            const auto it = lhatAt.find({partner.x, partner.y});
            if (it == lhatAt.end()) continue;
            const auto naiveLhat = [&](const ReflectorPixel& p) {
                return p.x == q.pixel.x && p.y == q.pixel.y ? p.lhat : it->second;
            };
            const glm::vec3 naive = k == 0 ? q.dFdxFine(naiveLhat) : q.dFdyFine(naiveLhat);
            ++naiveN;
            naiveClose += glm::length(gpu - naive) < 1e-3 + 1e-2 * glm::length(gpu);
        }
    }
    std::printf("fine derivatives of lhat within 1e-3 + 1%%: %ld of %ld mirror px (worst %.3g), "
                "%ld of %ld away from the silhouette (worst %.3g); mean |d| %.3g; the naive "
                "neighbour twin: %ld of %ld (%ld partners off the reflector)\n",
                close[0], n[0], worst[0], close[1], n[1], worst[1],
                n[0] ? scale / double(n[0]) : 0.0, naiveClose, naiveN, n[0] - naiveN);
    ASSERT_GT(n[1], 400);
    EXPECT_GT(scale / double(n[0]), 1e-3) << "the derivatives must not all vanish";
    EXPECT_GE(double(close[1]), 0.995 * double(n[1]));
    EXPECT_GE(double(close[0]), 0.98 * double(n[0]));
}
