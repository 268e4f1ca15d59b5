#include "sandbox/lib/walk/chase_path.h"

#include "engine/raytrace/embree_scene.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>

namespace specula {
namespace sandbox {

Polyline::Polyline(std::vector<glm::vec3> p) : points(std::move(p)) {
    cumulative.push_back(0.f);
    for (std::size_t i = 1; i < points.size(); ++i)
        cumulative.push_back(cumulative.back() + glm::distance(points[i - 1], points[i]));
}

std::pair<glm::vec3, glm::vec3> Polyline::at(float u) const {
    const float s = std::clamp(u, 0.f, 1.f) * length();
    std::size_t i = 1;
    while (i + 1 < points.size() && cumulative[i] < s)
        ++i;
    const float span = cumulative[i] - cumulative[i - 1];
    const float f = span > 0.f ? (s - cumulative[i - 1]) / span : 0.f;
    const glm::vec3 d = points[i] - points[i - 1];
    const float len = glm::length(d);
    return {glm::mix(points[i - 1], points[i], f), len > 0.f ? d / len : glm::vec3(1, 0, 0)};
}

CameraView chaseCamera(glm::vec3 p, glm::vec3 tangent, float side, int width, int height) {
    glm::vec3 across = glm::cross(tangent, glm::vec3(0, 1, 0));
    across = glm::length(across) > 1e-4f ? glm::normalize(across) : glm::vec3(0, 0, 1);
    const glm::vec3 eye = p + side * 1.5f * across + glm::vec3(0, 0.35f, 0);
    return CameraView::lookAt(eye, p, glm::vec3(0, 1, 0), glm::radians(50.f), width, height);
}

int unblockedFrames(const EmbreeScene& env, const Polyline& path, float side, int frames) {
    int clear = 0;
    for (int f = 0; f < frames; ++f) {
        const auto [p, t] = path.at(frames > 1 ? float(f) / float(frames - 1) : 0.f);
        const glm::vec3 eye = chaseCamera(p, t, side, 8, 8).eye();
        const float d = glm::distance(eye, p);
        if (!env.intersect(eye, (p - eye) / d, 1e-4f, d - 0.4f)) ++clear;
    }
    return clear;
}

} // namespace sandbox
} // namespace specula
