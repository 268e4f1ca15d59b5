// A light-field probe through the host API (LightFieldHostProbe): a host's own full-screen
// shader ray casts a sphere inside the room's light-field cell and calls speculaReflect, a
// mirror on the left half of the frame and roughness 0.35 on the right; every pixel is held to
// the CPU twin (CpuLightFieldProbe::reflectedRadiance) recomputed from the same camera and
// sphere: >= 40 dB, for the mirror library and the glossy one. Bad input is an error value.
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/lightfield/lightfield_host_probe.h"
#include "components/reflection_probe/lightfield/lightfield_probe_cpu.h"
#include "engine/context/context.h"
#include "engine/gpu/render_target.h"
#include "engine/image_io/compare.h"
#include "support/fullscreen_pass.h"
#include "support/host_sphere.h"
#include "support/probe_room.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

namespace specula {
namespace {

constexpr int kW = 128, kH = 96;
constexpr float kRough = 0.35f;

// The host's main after Specula's library and the sphere ray cast.
const char* kHostMain = R"(
uniform float uRough;
void main() {
    vec3 p, d;
    vec2 ndc;
    if (!sphereHit(p, d, ndc)) { colour = vec4(0.0); return; }
    colour = vec4(speculaReflect(p, p - uSphere.xyz, d, ndc.x < 0.0 ? 0.0 : uRough), 1.0);
}
)";

class HostLightField : public test::ScratchDirTest {
protected:
    HostLightField() : ScratchDirTest("specula-host-lightfield") {}
    static void SetUpTestSuite() { context_ = gpu::GlContext::createHeadless().release(); }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }
    std::string cook() {
        test::ProbeRoom room;
        LightFieldCookSettings s;
        s.cameras = 8;
        s.imageRes = 32;
        CookOptions o;
        o.out = (root_ / "lightfield").string();
        o.flavour = s;
        o.progress = false;
        cookProbe(room.probeScene(), o, nullptr);
        return (root_ / "lightfield" / "manifest.json").string();
    }
    static inline gpu::GlContext* context_ = nullptr;
};

TEST_F(HostLightField, ReflectsAsItsTwinDoesMirrorAndGlossy) {
    const std::string manifest = cook();
    for (const bool glossy : {false, true}) {
        const LightFieldHostResult made = LightFieldHostProbe::create(manifest, {.glossy = glossy});
        ASSERT_TRUE(made) << made.error;
        const LightFieldHostProbe& probe = *made.probe;
        const glm::vec3 c = probe.cellCentre();
        const glm::vec4 sphere(c, 0.5f * probe.halfCell());
        const glm::vec3 eye = c + glm::vec3(0.f, 0.3f, 1.6f);
        const test::HostSphereView view{
            glm::inverse(glm::perspective(glm::radians(35.f), float(kW) / kH, 0.05f, 100.f) *
                         glm::lookAt(eye, c, glm::vec3(0.f, 1.f, 0.f))),
            eye, sphere, kW, kH};
        gpu::Program prog = test::buildFullscreenProgram(
            "host_lightfield", probe.glslLibrary() + test::kHostSphereGlsl + kHostMain);
        gpu::RenderTarget target(kW, kH);
        const gpu::VertexArray vao = gpu::VertexArray::create();
        const Image host = test::drawFullscreen(target, prog, vao, [&] {
            view.setUniforms(prog);
            prog.setUniform("uRough", kRough);
            probe.bindTo(prog.id());
        });

        const CpuLightFieldProbe twin(probe.asset());
        Image reference(kW, kH, 4);
        int covered = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                glm::vec3 p, d;
                glm::vec2 ndc;
                const bool hit = view.hit(x, y, p, d, ndc);
                float* px = reference.at(x, y);
                if (!hit) {
                    px[3] = 0.f;
                    continue;
                }
                const glm::vec3 n = glm::normalize(p - glm::vec3(sphere));
                const glm::vec3 l = glm::normalize(d - 2.f * glm::dot(d, n) * n);
                const float r = glossy && ndc.x >= 0.f ? kRough : 0.f;
                const glm::vec3 v = twin.reflectedRadiance(p - c, l, n, r);
                std::copy(&v[0], &v[0] + 3, px);
                px[3] = 1.f;
                ++covered;
            }
        const ImageStats stats = compareImages(host, reference);
        std::printf("[host-lightfield] %s: %d sphere px: %s dB against the twin, max %.4f\n",
                    glossy ? "glossy" : "mirror", covered, formatPsnr(stats.psnr).c_str(),
                    stats.maxError);
        ASSERT_GT(covered, kW * kH / 8) << "the camera must see the sphere";
        ASSERT_TRUE(stats.hasPsnr);
        EXPECT_GE(stats.psnr, 40.0) << (glossy ? "glossy" : "mirror");
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
    }
}

TEST_F(HostLightField, BadInputIsAnErrorValueNamingTheFile) {
    const std::string missing = (root_ / "none" / "manifest.json").string();
    const LightFieldHostResult none = LightFieldHostProbe::create(missing);
    EXPECT_FALSE(none);
    EXPECT_NE(none.error.find(missing), std::string::npos) << none.error;

    const std::string manifest = cook();
    nlohmann::json j = nlohmann::json::parse(std::ifstream(manifest));
    j["cameras"] = -3;
    std::ofstream(manifest) << j.dump();
    const LightFieldHostResult bad = LightFieldHostProbe::create(manifest);
    EXPECT_FALSE(bad);
    EXPECT_NE(bad.error.find(manifest + ": cameras"), std::string::npos) << bad.error;
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

} // namespace
} // namespace specula
