#pragma once
// Draws a ReflectionScene with the rasteriser: environment through SceneRenderer, reflectors
// through ReflectionProbeSystem, into an offscreen float target. Needs a current GL context.
#include "components/reflection_probe/reflection_probe_system.h"
#include "engine/gpu/render_target.h"
#include "engine/render/scene_renderer.h"
#include "sandbox/lib/reflection_scene.h"

namespace specula {

class FrameRenderer {
public:
    FrameRenderer(ReflectionScene& scene, int width, int height);

    // Renders the current state; output 0 = colour, 1/2 = the reflector pixels' probe-local
    // position / reflected direction (inputs for the CPU twin; other pixels hold the scene).
    Image render(const CameraView& camera, int output = 0);
    // Environment and sky only, reflectors skipped (for rasteriser-vs-tracer checks).
    Image renderEnvironment(const CameraView& camera);

    const ProbeFrameStats& stats() const { return probes_.stats(); }
    ReflectionProbeSystem& probes() { return probes_; }
    SceneRenderer& sceneRenderer() { return renderer_; }
    gpu::RenderTarget& target() { return target_; }

private:
    ReflectionScene& scene_;
    SceneRenderer renderer_;
    ReflectionProbeSystem probes_;
    gpu::RenderTarget target_;
};

} // namespace specula
