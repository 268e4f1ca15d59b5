#include "reflector_pixels.h"

#include "engine/core/glsl_host.h"
#include "engine/raytrace/triangle_plane.h"

#include <algorithm>
#include <cmath>

namespace specula {
namespace glsl {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function" // schlickFresnel: the shader's, not ours
#include "components/reflection_probe/shaders/reflector_common.glsl.h"
#pragma GCC diagnostic pop
} // namespace
} // namespace glsl

float ReflectorPixel::cosView() const {
    return std::max(std::abs(glm::dot(normal, view)), 1e-4f);
}

namespace {

// What the reflector pass computes from the interpolated position and normal.
ReflectorPixel pixelOf(int x, int y, const Hit& hit, glm::vec3 dir) {
    ReflectorPixel p;
    p.x = x;
    p.y = y;
    p.position = hit.position;
    p.entity = hit.entity;
    p.uv = hit.uv;
    p.view = glm::normalize(dir);
    p.normal = glsl::safeNormal(hit.normal, hit.geometricNormal);
    p.lhat = glm::normalize(glsl::mirrorDirection(p.view, p.normal));
    return p;
}

// The partner pixel (x, y) shaded on the plane of `on`'s triangle; `self` when its ray runs
// parallel to the plane.
ReflectorPixel partnerOf(const ecs::Registry& registry, const CameraView& camera, int x, int y,
                         const Hit& on, const ReflectorPixel& self) {
    glm::vec3 origin, dir;
    camera.primaryRay(x, y, origin, dir);
    const std::optional<Hit> h = hitOnTrianglePlane(registry, on, origin, dir);
    return h ? pixelOf(x, y, *h, dir) : self;
}

// Visits every mirror-mask pixel whose primary ray hits the full scene, in row order.
template <class Visit>
void forEachReflectorHit(const GroundTruthTracer& tracer, const CameraView& camera,
                         const Image& mirrorMask, Visit&& visit) {
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            if (mirrorMask.at(x, y)[0] < 0.5f) continue;
            glm::vec3 origin, dir;
            camera.primaryRay(x, y, origin, dir);
            if (const std::optional<Hit> hit = tracer.fullScene().intersect(origin, dir))
                visit(x, y, *hit, dir);
        }
}

} // namespace

std::vector<ReflectorPixel> reflectorPixels(const GroundTruthTracer& tracer,
                                            const CameraView& camera, const Image& mirrorMask) {
    std::vector<ReflectorPixel> out;
    forEachReflectorHit(tracer, camera, mirrorMask, [&](int x, int y, const Hit& h, glm::vec3 d) {
        out.push_back(pixelOf(x, y, h, d));
    });
    return out;
}

std::vector<ReflectorQuadPixel> reflectorQuadPixels(const ecs::Registry& registry,
                                                    const GroundTruthTracer& tracer,
                                                    const CameraView& camera,
                                                    const Image& mirrorMask) {
    std::vector<ReflectorQuadPixel> out;
    forEachReflectorHit(tracer, camera, mirrorMask, [&](int x, int y, const Hit& h, glm::vec3 d) {
        ReflectorQuadPixel q;
        q.height = camera.height;
        q.pixel = pixelOf(x, y, h, d);
        q.acrossX = partnerOf(registry, camera, x ^ 1, y, h, q.pixel);
        const int partnerRow = camera.height - 1 - (q.windowRow() ^ 1);
        q.acrossY = partnerOf(registry, camera, x, partnerRow, h, q.pixel);
        out.push_back(q);
    });
    return out;
}

} // namespace specula
