// The host path, as a host programmer runs it: examples/minimal (its own context, shader and
// analytic mirror sphere and rough disc, Specula through DistanceHostProbe only) renders a
// probe of the bundled room headless, and every pixel is held to the CPU twin of the shader
// (CpuDistanceProbe's glossy sample times the GGX albedo, at roughness 0 for the mirror and
// 0.3 for the disc) recomputed here from the example's camera and geometry: >= 40 dB. Bad input
// reaches the host as an error value naming the asset, and it exits cleanly.
#include "assetcooker/lib/bake/cook.h"
#include "components/reflection_probe/distance/distance_glossy_chain.h"
#include "components/reflection_probe/distance/distance_gpu_probe.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "engine/image/ggx_albedo.h"
#include "engine/image_io/compare.h"
#include "support/probe_room.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

namespace specula {
namespace {

namespace fs = std::filesystem;

const fs::path kExample = fs::path(SPECULA_BIN_DIR) / "example_minimal";

// A PFM as examples/minimal writes it: "PF", size, -1 (little-endian), rows bottom to top.
Image readPfm(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string magic;
    int w = 0, h = 0;
    float scale = 0.f;
    in >> magic >> w >> h >> scale;
    in.get();
    Image image(w, h, 3);
    in.read(reinterpret_cast<char*>(image.pixels.data()), std::streamsize(image.pixels.size() * 4));
    if (magic != "PF" || scale >= 0.f || !in) return {};
    return image;
}

// What the example draws at pixel (x, y) (GL rows, bottom up), by the twin. Its camera and
// scene, repeated from examples/minimal/minimal.cpp.
struct HostScene {
    glm::vec3 centre, eye;
    glm::mat4 invViewProj;
    int w, h;
    HostScene(glm::vec3 c, int width, int height) : centre(c), w(width), h(height) {
        eye = c + glm::vec3(0.f, 0.45f, 1.6f);
        invViewProj = glm::inverse(
            glm::perspective(glm::radians(50.f), float(w) / float(h), 0.05f, 100.f) *
            glm::lookAt(eye, c - glm::vec3(0.f, 0.15f, 0.f), glm::vec3(0.f, 1.f, 0.f)));
    }
    glm::vec3 pixel(int x, int y, const CpuDistanceProbe& twin) const {
        const glm::vec2 ndc((x + 0.5f) / float(w) * 2.f - 1.f, (y + 0.5f) / float(h) * 2.f - 1.f);
        const glm::vec4 far = invViewProj * glm::vec4(ndc, 1.f, 1.f);
        const glm::vec3 d = glm::normalize(glm::vec3(far) / far.w - eye);
        const glm::vec3 sphere = centre, o = eye - sphere;
        const float b = glm::dot(o, d), c = glm::dot(o, o) - 0.09f, disc2 = b * b - c;
        const float tSphere = disc2 >= 0.f ? -b - std::sqrt(disc2) : -1.f;
        float tDisc = (centre.y - 0.45f - eye.y) / d.y;
        const glm::vec3 q = eye + tDisc * d - (centre - glm::vec3(0.f, 0.45f, 0.f));
        if (!(tDisc > 0.f && glm::dot(q, q) <= 0.81f)) tDisc = -1.f;
        const bool onSphere = tSphere > 0.f && (tDisc < 0.f || tSphere < tDisc);
        if (!onSphere && !(tDisc > 0.f)) return glm::vec3(0.f);
        const glm::vec3 p = eye + (onSphere ? tSphere : tDisc) * d;
        glm::vec3 n = onSphere ? glm::normalize(p - sphere) : glm::vec3(0.f, 1.f, 0.f);
        if (glm::dot(n, d) > 0.f) n = -n;
        const glm::vec3 l = glm::normalize(d - 2.f * glm::dot(d, n) * n); // the mirror ray
        // The example's probe is glossy: every pixel runs the chain's path, the mirror at
        // roughness 0 (level 0 of the chain), times the GGX albedo, as the shader does.
        const float r = onSphere ? 0.f : 0.3f;
        return twin.glossyRadiance(p - centre, l, r) * ggxAlbedo(std::abs(glm::dot(n, d)), r);
    }
};

class HostExample : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("host_example_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path dir_;
};

TEST_F(HostExample, RendersTheRoomProbeAsTheTwinDoes) {
    test::ProbeRoom room;
    DistanceCookSettings s;
    s.faceRes = 64;
    s.planned = s.recordPlan = false;
    CookOptions o;
    o.out = (dir_ / "probe").string();
    o.flavour = s;
    o.progress = false;
    cookProbe(room.probeScene(), o, nullptr);
    const std::string manifest = (dir_ / "probe" / "manifest.json").string();

    const int w = 160, h = 120;
    const test::ToolRun run = test::runShellTool(
        kExample, test::shellQuote(manifest) + " --headless --out " +
                      test::shellQuote((dir_ / "host.pfm").string()) + " --size 160 120");
    ASSERT_EQ(run.status, 0) << run.err;
    const Image host = readPfm(dir_ / "host.pfm");
    ASSERT_EQ(host.width, w);
    ASSERT_EQ(host.height, h);

    const auto asset = std::make_shared<const DistanceProbeAsset>(
        storedDistanceAsset(readDistanceProbe(manifest)));
    const DistanceLookupConfig config =
        makeLookupConfig(DistanceProbe{}, *asset); // Planned, as the host
    const CpuDistanceProbe twin(*asset, config,
                                std::make_shared<const CubeChain>(glossyChainOf(*asset)));
    const HostScene scene(asset->centre, w, h);
    Image reference(w, h, 3);
    int covered = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 c = scene.pixel(x, y, twin);
            std::copy(&c[0], &c[0] + 3, reference.at(x, y));
            covered += c != glm::vec3(0.f);
        }
    EXPECT_GT(covered, w * h / 4) << "the sphere and the disc fill a good part of the frame";
    const ImageStats stats = compareImages(host, reference);
    std::printf(
        "[host-example] %d x %d, %d reflector pixels: %s dB against the twin, max error %.4f\n", w,
        h, covered, formatPsnr(stats.psnr).c_str(), stats.maxError);
    ASSERT_TRUE(stats.hasPsnr);
    EXPECT_GE(stats.psnr, 40.0);
}

TEST_F(HostExample, ABadAssetIsAnErrorValueNamingIt) {
    fs::create_directories(dir_);
    std::ofstream(dir_ / "manifest.json")
        << R"({"format": "specula-probe", "version": 1, "flavour": "distance"})";
    const test::ToolRun old = test::runShellTool(
        kExample, test::shellQuote((dir_ / "manifest.json").string()) + " --headless");
    EXPECT_EQ(old.status, 1);
    EXPECT_NE(old.err.find("manifest.json: version: asset format 1"), std::string::npos) << old.err;
    EXPECT_NE(old.err.find("re-cook"), std::string::npos) << old.err;
    const test::ToolRun missing = test::runShellTool(
        kExample, test::shellQuote((dir_ / "none.json").string()) + " --headless");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("none.json"), std::string::npos) << missing.err;
}

} // namespace
} // namespace specula
