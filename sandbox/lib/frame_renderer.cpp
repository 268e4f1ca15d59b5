#include "frame_renderer.h"

namespace specula {

FrameRenderer::FrameRenderer(ReflectionScene& scene, int width, int height)
    : scene_(scene), target_(width, height) {
    if (!scene.sky().empty()) renderer_.setSky(scene.sky());
}

Image FrameRenderer::render(const CameraView& camera, int output) {
    ecs::Registry& reg = scene_.registry();
    renderer_.sync(reg);
    probes_.sync(reg);
    renderer_.render(camera, target_, [&](ecs::Entity e) { return reg.has<Reflector>(e); });
    probes_.render(reg, camera, renderer_, target_, output);
    return target_.readback();
}

Image FrameRenderer::renderEnvironment(const CameraView& camera) {
    ecs::Registry& reg = scene_.registry();
    renderer_.sync(reg);
    renderer_.render(camera, target_, [&](ecs::Entity e) { return scene_.isMirror(e); });
    return target_.readback();
}

} // namespace specula
