// The rasteriser and the Embree tracer must draw the same picture of the environment: this
// pins camera, handedness, texture orientation, sky mapping and shading conventions once for
// everything built on them.
#include "engine/image_io/compare.h"
#include "engine/image_io/image_io.h"
#include "probe_fixture.h"

#include <cstdio>

using namespace specula;
using specula::test::RoomProbe;

TEST_F(RoomProbe, RasteriserAndTracerAgreeOnTheEnvironment) {
    for (const CameraView& cam : {scene_->camera(kWidth, kHeight),
                                  scene_->orbitCamera(kWidth, kHeight, 2.1f, 3.0f, 1.2f)}) {
        const GroundTruthImage truth = scene_->groundTruth(cam, true);
        const Image raster = renderer_->renderEnvironment(cam);
        // Compare pixels that are environment in the tracer's eyes and away from any edge:
        // a silhouette pixel is covered by a triangle in one renderer and not in the other
        // (the rasteriser samples coverage, the tracer one ray), which says nothing about
        // conventions. Erode the non-mirror mask, and drop depth discontinuities.
        Image env(kWidth, kHeight, 1);
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                bool keep = truth.mirrorMask.at(x, y)[0] < 0.5f;
                const float d = truth.depth.at(x, y)[0];
                for (int dy = -1; dy <= 1 && keep; ++dy)
                    for (int dx = -1; dx <= 1 && keep; ++dx) {
                        const int xx = std::clamp(x + dx, 0, kWidth - 1);
                        const int yy = std::clamp(y + dy, 0, kHeight - 1);
                        const float dn = truth.depth.at(xx, yy)[0];
                        keep = truth.mirrorMask.at(xx, yy)[0] < 0.5f &&
                               (std::isinf(d) == std::isinf(dn)) &&
                               (std::isinf(d) || std::abs(dn - d) < 0.05f * d);
                    }
                env.at(x, y)[0] = keep ? 1.f : 0.f;
            }
        const ImageStats s = compareImages(raster, truth.color, &env);
        std::printf("rasteriser vs tracer: %zu px, PSNR %.2f dB, RMSE %.5f, max %.4f\n", s.pixels,
                    s.psnr, s.rmse, s.maxError);
        if (const char* out = std::getenv("SPECULA_TEST_OUT")) {
            writeImage(std::string(out) + "/raster.png", raster);
            writeImage(std::string(out) + "/traced.png", truth.color);
        }
        ASSERT_GT(s.pixels, size_t(kWidth * kHeight / 2));
        // Same shading code, same sampling rules (GL_LINEAR without mipmaps both sides), same
        // pixel centres: what remains is float rounding and the GPU's 8-bit filter weights
        // on high-contrast textures (up to ~1/256 of a texel step). 40 dB is an RMSE of 1 %;
        // a flipped axis, a mirrored texture or a half-pixel shift costs far more (< 20 dB).
        EXPECT_GT(s.psnr, 40.0);
        // Control: the same comparison against the tracer's picture mirrored left-right must
        // fail the bar by far, or the threshold would not catch a handedness mistake.
        Image mirrored = truth.color;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x)
                for (int c = 0; c < mirrored.channels; ++c)
                    mirrored.at(x, y)[c] = truth.color.at(kWidth - 1 - x, y)[c];
        const double mirroredPsnr = compareImages(raster, mirrored, &env).psnr;
        std::printf("  control, tracer mirrored: PSNR %.2f dB\n", mirroredPsnr);
        EXPECT_LT(mirroredPsnr, 30.0);
    }
}
