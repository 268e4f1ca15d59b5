// A level of distance probes through the host API (DistanceLevelHostProbe): a host's own
// full-screen shader ray casts a mirror sphere in the two-room scene's doorway, where both
// probes have influence, and calls speculaReflect; every pixel is held to the level's CPU twin
// (CpuDistanceLevel) for the visibility blend at K = 4: >= 40 dB. The per-reflector data: a
// reflector's bounds select the probes whose influence meets them. Bad input is an error value.
#include "components/reflection_probe/distance/distance_level_cpu.h"
#include "components/reflection_probe/distance/distance_level_host_probe.h"
#include "engine/gpu/render_target.h"
#include "engine/image_io/compare.h"
#include "support/fullscreen_pass.h"
#include "support/host_sphere.h"
#include "two_room_level_gpu_fixture.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace specula {
namespace {

constexpr int kW = 160, kH = 120;
const glm::vec4 kSphere(0.2f, 1.2f, 0.f, 0.35f); // in the doorway (the wall at x = 0)

class HostLevel : public test::TwoRoomLevelGpuTest {
protected:
    HostLevel() : TwoRoomLevelGpuTest("specula-host-level") {}
};

TEST_F(HostLevel, BlendsTheLevelAsItsTwinDoes) {
    test::ProbeRoom room(test::kTwoRoomsScene, "");
    const std::string index = bake(room);
    DistanceLevelHostOptions options;
    options.settings.lookup.method = DistanceMethod::Secant;
    options.settings.blend = LevelBlend::Visibility;
    options.settings.k = 4;
    const DistanceLevelHostResult made = DistanceLevelHostProbe::create(index, options);
    ASSERT_TRUE(made) << made.error;
    const DistanceLevelHostProbe& level = *made.probe;

    const Aabb sphereBounds = Aabb::cube(glm::vec3(kSphere), kSphere.w);
    EXPECT_EQ(level.probesFor(sphereBounds).size(), 2u) << "the doorway is in both influences";
    EXPECT_EQ(level.probesFor(Aabb::cube(glm::vec3(-3.f, 1.2f, 0.f), 0.2f)).size(), 1u)
        << "deep in room A only its probe";

    const CameraView cam = doorwayCamera(kW, kH);
    const test::HostSphereView view{glm::inverse(cam.viewProj()), cam.eye(), kSphere, kW, kH};
    gpu::Program prog = test::buildFullscreenProgram(
        "host_level", level.glslLibrary() + test::kHostSphereGlsl + test::kHostMirrorSphereMain);
    gpu::RenderTarget target(kW, kH);
    const gpu::VertexArray vao = gpu::VertexArray::create();
    const Image host = test::drawFullscreen(target, prog, vao, [&] {
        view.setUniforms(prog);
        level.bindTo(prog.id(), sphereBounds);
    });

    const CpuDistanceLevel twin(index, options.settings.lookup);
    Image reference(kW, kH, 3);
    int covered = 0, blended = 0;
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            glm::vec3 p, d;
            glm::vec2 ndc;
            if (!view.hit(x, y, p, d, ndc)) continue;
            const glm::vec3 n = glm::normalize(p - glm::vec3(kSphere));
            const glm::vec3 l = glm::normalize(d - 2.f * glm::dot(d, n) * n);
            const LevelSample s = twin.radiance(p, l, LevelBlend::Visibility, 4);
            std::copy(&s.radiance[0], &s.radiance[0] + 3, reference.at(x, y));
            ++covered;
            blended += s.weights.size() >= 2 ? 1 : 0;
        }
    const ImageStats stats = compareImages(host, reference);
    std::printf(
        "[host-level] %d sphere px (%d blend 2+ probes): %s dB against the twin, max %.4f\n",
        covered, blended, formatPsnr(stats.psnr).c_str(), stats.maxError);
    ASSERT_GT(covered, 1000) << "the camera must see the sphere";
    ASSERT_TRUE(stats.hasPsnr);
    EXPECT_GE(stats.psnr, 40.0);
}

TEST_F(HostLevel, BadInputIsAnErrorValueNamingTheFile) {
    const DistanceLevelHostResult missing =
        DistanceLevelHostProbe::create((root_ / "none" / "level.json").string());
    EXPECT_FALSE(missing);
    EXPECT_NE(missing.error.find("level.json"), std::string::npos) << missing.error;

    test::ProbeRoom room(test::kTwoRoomsScene, "");
    const std::string index = bake(room);
    DistanceLevelHostOptions layered;
    layered.settings.lookup.method = DistanceMethod::Layered; // a level looks up composites only
    const DistanceLevelHostResult refused = DistanceLevelHostProbe::create(index, layered);
    EXPECT_FALSE(refused);
    EXPECT_NE(refused.error.find("level.json"), std::string::npos) << refused.error;
}

} // namespace
} // namespace specula
