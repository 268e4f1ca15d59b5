// The distance-cubemap shader against its CPU twin and against the Embree ground truth, on
// the default room.
#include "engine/image_io/compare.h"
#include "engine/image_io/image_io.h"
#include "probe_fixture.h"
#include "twin_agreement.h"

#include <cstdio>
#include <iterator>
#include <vector>

using namespace specula;
using specula::test::RoomProbe;

namespace {

const DistanceMethod kMethods[] = {DistanceMethod::Envmap,    DistanceMethod::BoxProj,
                                   DistanceMethod::Bisection, DistanceMethod::Secant,
                                   DistanceMethod::AvgDist,   DistanceMethod::Layered,
                                   DistanceMethod::March}; // the peer (Szirmay-Kalos 2005)
constexpr int kMethodCount = int(std::size(kMethods));

double psnrOf(const Image& a, const Image& b, const Image& mask) {
    return compareImages(a, b, &mask).psnr;
}

} // namespace

TEST_F(RoomProbe, ShaderMatchesCpuTwinPerPixel) {
    // The twin runs on the exact inputs the shader used (its probe-local position and
    // reflected direction, read back as float32), so layer lookups must agree to filtering
    // precision. Rays that end in the sky go through equirectUv's atan/acos, which GPUs
    // evaluate with approximations (llvmpipe ~1e-5 rad); on the high-frequency panorama that
    // moves the bilinear sample by a fraction of a texel, hence the looser sky bound.
    const CameraView cam = scene_->camera(kWidth, kHeight);
    const Image mask = erodedMask(scene_->groundTruth(cam, true).mirrorMask);
    // Layered twice: bisection on every object layer (the default), then the cooked methods
    // (the average distance on the small layers, issue 15's point on the layer's box span).
    std::vector<DistanceProbe> probes;
    for (DistanceMethod m : kMethods)
        probes.push_back(probeFor(m));
    probes.push_back(probeFor(DistanceMethod::Layered));
    probes.back().layerMethod = DistanceMethod::Envmap; // not per layer: the cooked methods
    for (const DistanceProbe& p : probes) {
        const DistanceMethod m = p.method;
        useProbe(p);
        const test::TwinAgreement t = test::compareWithTwin(*renderer_, *scene_, cam, mask);
        ASSERT_GT(t.layerPx, 500) << "the camera must see the reflectors";
        std::printf("%-9s%s twin vs GLSL: %ld layer px, %.3f%% within 2e-3, mean %.2e, worst %.4f; "
                    "%ld sky px, worst %.4f\n",
                    toString(m), p.layerMethod == DistanceMethod::Envmap ? " (cooked)" : "",
                    t.layerPx, 100.0 * t.share(), t.mean(), t.worst, t.skyPx, t.worstSky);
        // A nearest distance fetch right on a texel boundary can flip on the last bit of a
        // float between GPU and CPU and end the search one texel apart: allow 0.5 % of pixels.
        EXPECT_GT(t.share(), 0.995) << toString(m);
        EXPECT_LT(t.mean(), 5e-4) << toString(m);
        EXPECT_LT(t.worstSky, 0.03) << toString(m);
    }
}

TEST_F(RoomProbe, RectificationBeatsEnvmapAndBoxProjAgainstGroundTruth) {
    const CameraView cam = scene_->camera(kWidth, kHeight);
    const GroundTruthImage envOnly = scene_->groundTruth(cam, true);
    const GroundTruthImage full = scene_->groundTruth(cam, false);
    const Image mask = erodedMask(envOnly.mirrorMask);
    double psnr[kMethodCount] = {};
    for (int i = 0; i < kMethodCount; ++i) {
        useProbe(probeFor(kMethods[i]));
        const Image img = renderer_->render(cam);
        psnr[i] = psnrOf(img, envOnly.color, mask);
        if (const char* out = std::getenv("SPECULA_TEST_OUT")) {
            writeImage(std::string(out) + "/" + toString(kMethods[i]) + ".png", img);
            writeImage(std::string(out) + "/truth_env_only.png", envOnly.color);
            writeImage(std::string(out) + "/err_" + toString(kMethods[i]) + ".png",
                       errorHeatmap(img, envOnly.color, &mask, 0.2f));
        }
        std::printf("%-9s PSNR vs env-only ground truth %.2f dB, vs full ground truth %.2f dB\n",
                    toString(kMethods[i]), psnr[i], psnrOf(img, full.color, mask));
    }
    const double envmap = psnr[0], boxproj = psnr[1], bisection = psnr[2];
    EXPECT_GT(bisection, envmap + 6.0) << "bisection " << bisection << " dB, envmap " << envmap;
    EXPECT_GT(bisection, boxproj + 3.0) << "bisection " << bisection << " dB, boxproj " << boxproj;
    EXPECT_GT(psnr[3], envmap + 6.0) << "secant";
    EXPECT_GT(psnr[6], envmap + 6.0) << "march";
}

TEST_F(RoomProbe, LayersShowOcclusionAndParallaxLikeTheGroundTruth) {
    // Move the reflectors between two positions inside the cell: the reflected columns slide
    // over the walls behind them. The layered lookup must follow the ground truth at both,
    // and its change between the two must be the ground truth's change.
    const CameraView cam = scene_->camera(kWidth, kHeight);
    useProbe(probeFor(DistanceMethod::Layered));
    const glm::vec3 offsets[2] = {glm::vec3(-0.35f, 0.f, 0.2f), glm::vec3(0.35f, 0.f, -0.2f)};
    Image probeImg[2], truth[2], mask[2];
    for (int i = 0; i < 2; ++i) {
        scene_->setReflectorOffset(offsets[i]);
        const GroundTruthImage gt = scene_->groundTruth(cam, true);
        truth[i] = gt.color;
        mask[i] = erodedMask(gt.mirrorMask);
        probeImg[i] = renderer_->render(cam);
        useProbe(probeFor(DistanceMethod::Envmap));
        const Image env = renderer_->render(cam);
        useProbe(probeFor(DistanceMethod::Layered));
        const double layered = psnrOf(probeImg[i], truth[i], mask[i]);
        const double envmap = psnrOf(env, truth[i], mask[i]);
        std::printf("offset %d: layered %.2f dB, envmap %.2f dB\n", i, layered, envmap);
        EXPECT_GT(layered, envmap + 5.0);
    }
    scene_->setReflectorOffset(glm::vec3(0.f));
    // Pixels that are mirror in both frames: the change of the probe image should match the
    // change of the ground truth far better than "no change" does.
    Image both(kWidth, kHeight, 1);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            both.at(x, y)[0] = mask[0].at(x, y)[0] * mask[1].at(x, y)[0];
    double errChange = 0, errStatic = 0;
    long n = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            if (both.at(x, y)[0] < 0.5f) continue;
            const glm::vec3 dTruth = glm::vec3(truth[1].rgba(x, y) - truth[0].rgba(x, y));
            const glm::vec3 dProbe = glm::vec3(probeImg[1].rgba(x, y) - probeImg[0].rgba(x, y));
            errChange += glm::dot(dProbe - dTruth, dProbe - dTruth);
            errStatic += glm::dot(dTruth, dTruth);
            ++n;
        }
    ASSERT_GT(n, 200);
    std::printf("parallax: residual %.4f of the ground truth's change energy\n",
                errChange / errStatic);
    EXPECT_LT(errChange, 0.25 * errStatic);
}
