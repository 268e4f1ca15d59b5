#pragma once
// The reflector pixels of a camera as the ground-truth tracer sees them: where the primary
// ray meets a mirror, the point, the shading normal and the mirror direction computed as
// the reflector pass computes them (shaders/reflector_common.glsl.h). What a CPU twin is
// run on to draw a frame the way the shader would, for the walks, the benches and the tests.
#include "engine/image/image.h"
#include "engine/math/camera.h"
#include "engine/raytrace/ground_truth.h"

#include <glm/vec3.hpp>

#include <vector>

namespace specula {

struct ReflectorPixel {
    int x = 0, y = 0;
    glm::vec3 position{0.f}; // world space
    glm::vec3 normal{0.f};   // unit shading normal (safeNormal)
    glm::vec3 view{0.f};     // unit, eye to surface
    glm::vec3 lhat{0.f};     // unit mirror direction (mirrorDirection)
    float cosView() const;   // |n . v|, at least 1e-4
};

// Every pixel of `mirrorMask` (> 0.5) whose primary ray hits the tracer's full scene.
std::vector<ReflectorPixel> reflectorPixels(const GroundTruthTracer& tracer,
                                            const CameraView& camera, const Image& mirrorMask);

} // namespace specula
