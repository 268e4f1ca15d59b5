#pragma once
// The reflected rays of a camera's reflector pixels with the environment the ground truth sees
// along each: the mirror direction about the shading normal turned to the viewer, traced
// from just off the surface along the geometric normal. What the lookup tests score a
// probe's search against, ray by ray.
#include "engine/math/camera.h"
#include "engine/raytrace/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace specula::test {

struct MirrorRay {
    glm::vec3 position{0.f}; // world space, on the reflector
    glm::vec3 dir{0.f};      // unit reflected direction
    EnvSample env;           // the environment along it (Embree)
};

// Every pixel of `camera` whose primary ray meets a mirror of `options`, in row order.
inline std::vector<MirrorRay> mirrorRays(const GroundTruthTracer& tracer,
                                         const TraceOptions& options, const CameraView& camera) {
    std::vector<MirrorRay> rays;
    for (int py = 0; py < camera.height; ++py)
        for (int px = 0; px < camera.width; ++px) {
            glm::vec3 origin, d;
            camera.primaryRay(px, py, origin, d);
            const auto h = tracer.fullScene().intersect(origin, d);
            if (!h || !options.mirrors.contains(h->entity)) continue;
            d = glm::normalize(d);
            const glm::vec3 n = glm::dot(h->normal, d) > 0.f ? -h->normal : h->normal;
            const glm::vec3 ng =
                glm::dot(h->geometricNormal, d) > 0.f ? -h->geometricNormal : h->geometricNormal;
            const glm::vec3 r = glm::normalize(glm::reflect(d, n));
            const float m = std::max(
                {std::abs(h->position.x), std::abs(h->position.y), std::abs(h->position.z), 1.f});
            rays.push_back(
                {h->position, r, tracer.traceEnvironment(h->position + 1e-4f * m * ng, r)});
        }
    return rays;
}

} // namespace specula::test
