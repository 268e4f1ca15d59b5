#pragma once
// Draws a ReflectionScene with the rasteriser: environment through SceneRenderer, reflectors
// through ReflectionProbeSystem, into an offscreen float target. Needs a current GL context.
#include "components/reflection_probe/system/reflection_probe_system.h"
#include "engine/gpu/render_target.h"
#include "engine/render/scene_renderer.h"
#include "sandbox/lib/render/reflection_scene.h"

namespace specula {

class FrameRenderer {
public:
    FrameRenderer(ReflectionScene& scene, int width, int height);

    // Renders the current state; output 0 = colour, 1/2 = the reflector pixels' probe-local
    // position / reflected direction (inputs for the CPU twin; other pixels hold the scene).
    Image render(const CameraView& camera, int output = 0);
    // The same frame left in target() without a readback (timing loops).
    void draw(const CameraView& camera, int output = 0);
    // Environment and sky only, reflectors skipped (for rasteriser-vs-tracer checks).
    Image renderEnvironment(const CameraView& camera);

    const ProbeFrameStats& stats() const { return probes_.stats(); }
    // Time of the last draw's reflector pass. GL timer queries (stats().reflectorPassMs) on a
    // GPU; on a software rasteriser, whose TIME_ELAPSED queries do not cover its deferred
    // rasterisation (llvmpipe answers ~30 ns for most frames), the wall clock between two
    // glFinish calls around the pass. SPECULA_TIMER=gl|wall forces either.
    double passMs() const;
    // Time of the last draw's whole frame (the environment, the sky and the reflectors, their
    // per-frame uploads included): the wall clock between glFinish calls before and after it,
    // on any renderer, so it holds what a player waits for, not one pass's GPU time.
    double frameMs() const { return frameMs_; }
    const char* timerSource() const {
        return wallClock_ ? "wall clock around the pass (glFinish)" : "GL timer query";
    }
    ReflectionProbeSystem& probes() { return probes_; }
    SceneRenderer& sceneRenderer() { return renderer_; }
    gpu::RenderTarget& target() { return target_; }

private:
    ReflectionScene& scene_;
    SceneRenderer renderer_;
    ReflectionProbeSystem probes_;
    gpu::RenderTarget target_;
    bool wallClock_ = false;
    double wallMs_ = 0.0;
    double frameMs_ = 0.0;
};

// Median reflector-pass time over enough frames: batches until the median moves by less than
// 2 % (after minFrames), or maxFrames; `frames` gets the samples it rests on, `frameMs` (when
// given) the median whole-frame time of the same frames. The first frames after a probe
// change are warm-up (shader compile, texture upload) and dropped.
double timeReflectorPass(FrameRenderer& fr, const CameraView& cam, int minFrames, int maxFrames,
                         int& frames, double* frameMs = nullptr);

// GL_RENDERER names a CPU rasteriser (llvmpipe, softpipe, SwiftShader).
bool softwareRasteriser();

} // namespace specula
