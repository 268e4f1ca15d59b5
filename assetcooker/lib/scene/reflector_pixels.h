#pragma once
// The reflector pixels of a camera as the ground-truth tracer sees them: where the primary
// ray meets a mirror, the point, the shading normal and the mirror direction computed as
// the reflector pass computes them (shaders/reflector_common.glsl.h). What a CPU twin is
// run on to draw a frame the way the shader would, for the walks, the benches and the tests.
#include "engine/ecs/registry.h"
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
    ecs::Entity entity;      // the reflector mesh the primary ray met
    glm::vec2 uv{0.f};       // its TEXCOORD_0 there (zero without one), for a roughness map
    float cosView() const;   // |n . v|, at least 1e-4
};

// Every pixel of `mirrorMask` (> 0.5) whose primary ray hits the tracer's full scene.
std::vector<ReflectorPixel> reflectorPixels(const GroundTruthTracer& tracer,
                                            const CameraView& camera, const Image& mirrorMask);

// A reflector pixel with its two partners in the GPU's 2 x 2 pixel quad, shaded as the GPU
// shades them: on the plane of the pixel's own triangle, attributes extrapolated
// (engine/raytrace/triangle_plane.h), whether or not the triangle, or any reflector, covers
// them. What a twin needs of anything a shader differentiates (a MIP level, a footprint).
// Quads are the GL window's: pixel columns (2i, 2i + 1), and window rows (2j, 2j + 1)
// counted from the bottom, the image's last row being window row 0.
struct ReflectorQuadPixel {
    ReflectorPixel pixel;
    ReflectorPixel acrossX; // the partner in the same row
    ReflectorPixel acrossY; // the partner in the same column
    int height = 0;         // of the image: the window rows from its rows

    // GLSL's dFdxFine(f) and dFdyFine(f) at this pixel, of any f(const ReflectorPixel&):
    // along the window's x (right) and y (up).
    template <class F> auto dFdxFine(F f) const {
        return (pixel.x & 1) ? f(pixel) - f(acrossX) : f(acrossX) - f(pixel);
    }
    template <class F> auto dFdyFine(F f) const {
        return (windowRow() & 1) ? f(pixel) - f(acrossY) : f(acrossY) - f(pixel);
    }
    int windowRow() const { return height - 1 - pixel.y; }
};

// reflectorPixels with each pixel's quad partners; `registry` is the tracer's. A partner
// whose ray runs parallel to the triangle's plane is the pixel itself (a zero derivative).
std::vector<ReflectorQuadPixel> reflectorQuadPixels(const ecs::Registry& registry,
                                                    const GroundTruthTracer& tracer,
                                                    const CameraView& camera,
                                                    const Image& mirrorMask);

} // namespace specula
