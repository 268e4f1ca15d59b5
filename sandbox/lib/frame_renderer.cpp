#include "frame_renderer.h"

#include <epoxy/gl.h>

#include <chrono>
#include <cstdlib>
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
    ecs::Registry& reg = scene_.registry();
    renderer_.sync(reg);
    probes_.sync(reg);
    renderer_.render(camera, target_, [&](ecs::Entity e) { return reg.has<Reflector>(e); });
    if (!wallClock_) {
        probes_.render(reg, camera, renderer_, target_, output);
        return;
    }
    // The environment's work must not land inside the measured interval, nor the pass's
    // outside it.
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    probes_.render(reg, camera, renderer_, target_, output);
    glFinish();
    wallMs_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double FrameRenderer::passMs() const {
    return wallClock_ ? wallMs_ : probes_.stats().reflectorPassMs;
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
