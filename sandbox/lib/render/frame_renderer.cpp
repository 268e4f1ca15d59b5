#include "sandbox/lib/render/frame_renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace specula {

FrameRenderer::FrameRenderer(ReflectionScene& scene, int width, int height)
    : scene_(scene), target_(width, height) {
    if (!scene.sky().empty()) renderer_.setSky(scene.sky());
    const char* force = std::getenv("SPECULA_TIMER");
    wallClock_ = force ? std::string(force) == "wall" : softwareRasteriser();
}

Image FrameRenderer::render(const CameraView& camera, int output) {
    draw(camera, output);
    return target_.readback();
}

void FrameRenderer::draw(const CameraView& camera, int output) {
    using Clock = std::chrono::steady_clock;
    const auto ms = [](Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double, std::milli>(b - a).count();
    };
    ecs::Registry& reg = scene_.registry();
    glFinish(); // the previous frame's work stays out of this one's
    const auto frameStart = Clock::now();
    renderer_.sync(reg);
    probes_.sync(reg);
    renderer_.render(camera, target_, [&](ecs::Entity e) { return reg.has<Reflector>(e); });
    if (!wallClock_) {
        probes_.render(reg, camera, renderer_, target_, output);
        glFinish();
        frameMs_ = ms(frameStart, Clock::now());
        return;
    }
    // The environment's work must not land inside the measured interval, nor the pass's
    // outside it.
    glFinish();
    const auto t0 = Clock::now();
    probes_.render(reg, camera, renderer_, target_, output);
    glFinish();
    const auto t1 = Clock::now();
    wallMs_ = ms(t0, t1);
    frameMs_ = ms(frameStart, t1);
}

double FrameRenderer::passMs() const {
    return wallClock_ ? wallMs_ : probes_.stats().reflectorPassMs;
}

// Median reflector-pass time over enough frames: batches until the median moves by less than
// 2 % (after minFrames), or maxFrames. The first frames after a probe change are warm-up
// (shader compile, texture upload; llvmpipe's first timer query can be garbage) and dropped.
double timeReflectorPass(FrameRenderer& fr, const CameraView& cam, int minFrames, int maxFrames,
                         int& frames, double* frameMs) {
    for (int i = 0; i < 2; ++i)
        fr.draw(cam);
    std::vector<double> samples, frameSamples;
    double previous = std::numeric_limits<double>::quiet_NaN();
    const int batch = std::max(2, minFrames / 2);
    while (int(samples.size()) < maxFrames) {
        for (int i = 0; i < batch && int(samples.size()) < maxFrames; ++i) {
            fr.draw(cam);
            samples.push_back(fr.passMs());
            frameSamples.push_back(fr.frameMs());
        }
        const double m = gpu::medianMs(samples);
        if (int(samples.size()) >= minFrames && std::isfinite(m) && std::isfinite(previous) &&
            std::abs(m - previous) <= 0.02 * m)
            break;
        previous = m;
    }
    frames = int(
        std::count_if(samples.begin(), samples.end(), [](double s) { return std::isfinite(s); }));
    if (frameMs) *frameMs = gpu::medianMs(frameSamples);
    return gpu::medianMs(samples);
}

bool softwareRasteriser() {
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const std::string s = r ? r : "";
    return s.find("llvmpipe") != std::string::npos || s.find("softpipe") != std::string::npos ||
           s.find("SwiftShader") != std::string::npos;
}

Image FrameRenderer::renderEnvironment(const CameraView& camera) {
    ecs::Registry& reg = scene_.registry();
    renderer_.sync(reg);
    renderer_.render(camera, target_, [&](ecs::Entity e) { return scene_.isMirror(e); });
    return target_.readback();
}

} // namespace specula
