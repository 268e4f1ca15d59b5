// A PEM probe through the host API (PemHostProbe): a host's own full-screen shader ray casts a
// mirror sphere inside the probe's box and calls speculaReflect; every pixel is held to the CPU
// twin (PemProbeCpu on the parameter block the host set) recomputed from the same camera and
// sphere: >= 40 dB, for box and distance geometry, at a parameter between two samples and after
// moving it (setSettings rewrites the block only), with float maps and with BC6H maps (sampled
// from their blocks, the twin reading their decoding). Bad input is an error value. (Measured:
// box 92 dB; distance 49-53 dB, where the random distance cube makes the search jump between
// texels at the few pixels whose float ray differs by an ulp from the twin's.)
#include "components/reflection_probe/pem/pem_host_probe.h"
#include "components/reflection_probe/pem/pem_probe_cpu.h"
#include "components/reflection_probe/pem/writer/pem_compression.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "engine/context/context.h"
#include "engine/gpu/render_target.h"
#include "engine/image_io/compare.h"
#include "pem/pem_random_asset.h"
#include "support/fullscreen_pass.h"
#include "support/host_sphere.h"
#include "support/scratch_dir_test.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

namespace specula {
namespace {

constexpr int kW = 128, kH = 96;

struct HostPemCase {
    bool distance = false;
    bool compressed = false;
};

class HostPem : public test::ScratchDirTest, public ::testing::WithParamInterface<HostPemCase> {
protected:
    HostPem() : ScratchDirTest("specula-host-pem") {}
    static void SetUpTestSuite() { context_ = gpu::GlContext::createHeadless().release(); }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }
    std::string write(bool distanceGeometry, bool compressed = false) {
        PemAsset a =
            test::randomAsset(16, 3, glm::vec3(-2.f, -1.f, -3.f), glm::vec3(2.f, 3.f, 2.f));
        if (distanceGeometry) test::addDistanceGeometry(a, 16);
        if (compressed) compressPemMaps(a);
        writePemProbe(a, (root_ / "pem").string(), "");
        return (root_ / "pem" / "manifest.json").string();
    }
    static inline gpu::GlContext* context_ = nullptr;
};

TEST_P(HostPem, ReflectsAsItsTwinDoesAtAnyParameter) {
    const auto [distance, compressed] = GetParam();
    const std::string manifest = write(distance, compressed);
    const PemHostResult made = PemHostProbe::create(manifest, {.settings = {.parameter = 0.3f}});
    ASSERT_TRUE(made) << made.error;
    PemHostProbe& probe = *made.probe;
    // Compressed maps are sampled from their blocks: BPTC storage, a sixteenth of RGBA32F's
    // bytes (3 samples x 6 faces x 16^2 texels at 1 byte).
    GLint format = 0;
    glGetTextureLevelParameteriv(probe.gpu().maps.id(), 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    EXPECT_EQ(GLenum(format),
              compressed ? GLenum(GL_COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT) : GLenum(GL_RGBA32F));
    EXPECT_EQ(pemDistantMapBytes(probe.asset()), std::size_t(3 * 6 * 256) * (compressed ? 1 : 16));
    const glm::vec3 c = probe.asset().centre;
    const glm::vec3 eye = c + glm::vec3(0.f, 0.3f, 1.2f);
    const test::HostSphereView view{
        glm::inverse(glm::perspective(glm::radians(40.f), float(kW) / kH, 0.05f, 100.f) *
                     glm::lookAt(eye, c, glm::vec3(0.f, 1.f, 0.f))),
        eye, glm::vec4(c, 0.3f), kW, kH};
    gpu::Program prog = test::buildFullscreenProgram(
        "host_pem", probe.glslLibrary() + test::kHostSphereGlsl + test::kHostMirrorSphereMain);
    gpu::RenderTarget target(kW, kH);
    const gpu::VertexArray vao = gpu::VertexArray::create();
    for (const float parameter : {0.3f, 0.8f}) {
        probe.setSettings({.parameter = parameter});
        const Image host = test::drawFullscreen(target, prog, vao, [&] {
            view.setUniforms(prog);
            probe.bindTo(prog.id());
        });
        const glsl::PemParams params = probe.gpu().params;
        ASSERT_GT(params.wb, 0.f) << "between two samples";
        const PemProbeCpu twin(probe.asset(), params);
        Image reference(kW, kH, 4);
        int covered = 0;
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                glm::vec3 p, d;
                glm::vec2 ndc;
                float* px = reference.at(x, y);
                if (!view.hit(x, y, p, d, ndc)) {
                    px[3] = 0.f;
                    continue;
                }
                const glm::vec3 n = glm::normalize(p - c);
                const glm::vec3 l = glm::normalize(d - 2.f * glm::dot(d, n) * n);
                const glm::vec3 v = twin.radiance(p - c, l);
                std::copy(&v[0], &v[0] + 3, px);
                px[3] = 1.f;
                ++covered;
            }
        const ImageStats stats = compareImages(host, reference);
        std::printf("[host-pem] %s geometry, %s maps, parameter %.1f: %d sphere px: %s dB "
                    "against the twin, max %.4f\n",
                    distance ? "distance" : "box", compressed ? "BC6H" : "float", parameter,
                    covered, formatPsnr(stats.psnr).c_str(), stats.maxError);
        ASSERT_GT(covered, kW * kH / 8) << "the camera must see the sphere";
        ASSERT_TRUE(stats.hasPsnr);
        EXPECT_GE(stats.psnr, 40.0);
    }
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

INSTANTIATE_TEST_SUITE_P(Geometry, HostPem,
                         ::testing::Values(HostPemCase{false, false}, HostPemCase{true, false},
                                           HostPemCase{false, true}, HostPemCase{true, true}),
                         [](const auto& info) {
                             return std::string(info.param.distance ? "Distance" : "Box") +
                                    (info.param.compressed ? "Bc6h" : "");
                         });

using HostPemInput = HostPem;

TEST_F(HostPemInput, BadInputIsAnErrorValueNamingTheFile) {
    const std::string missing = (root_ / "none" / "manifest.json").string();
    const PemHostResult none = PemHostProbe::create(missing);
    EXPECT_FALSE(none);
    EXPECT_NE(none.error.find(missing), std::string::npos) << none.error;
    const std::string manifest = write(false);
    nlohmann::json j = nlohmann::json::parse(std::ifstream(manifest));
    j["face_res"] = 0;
    std::ofstream(manifest) << j.dump();
    const PemHostResult bad = PemHostProbe::create(manifest);
    EXPECT_FALSE(bad);
    EXPECT_NE(bad.error.find(manifest + ": face_res"), std::string::npos) << bad.error;
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

} // namespace
} // namespace specula
