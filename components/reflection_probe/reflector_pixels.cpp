#include "reflector_pixels.h"

#include "engine/core/glsl_host.h"

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

std::vector<ReflectorPixel> reflectorPixels(const GroundTruthTracer& tracer,
                                            const CameraView& camera, const Image& mirrorMask) {
    std::vector<ReflectorPixel> out;
    for (int y = 0; y < camera.height; ++y)
        for (int x = 0; x < camera.width; ++x) {
            if (mirrorMask.at(x, y)[0] < 0.5f) continue;
            glm::vec3 origin, dir;
            camera.primaryRay(x, y, origin, dir);
            const std::optional<Hit> hit = tracer.fullScene().intersect(origin, dir);
            if (!hit) continue;
            ReflectorPixel p;
            p.x = x;
            p.y = y;
            p.position = hit->position;
            p.view = glm::normalize(dir);
            p.normal = glsl::safeNormal(hit->normal, hit->geometricNormal);
            p.lhat = glm::normalize(glsl::mirrorDirection(p.view, p.normal));
            out.push_back(p);
        }
    return out;
}

} // namespace specula
