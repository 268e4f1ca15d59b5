#pragma once
// Closed-form distance probes for tests: the environment is an axis-aligned box (probe-local)
// whose surface radiance is a smooth function of position, so the exact reflection of any
// ray is known without a renderer.
#include "components/reflection_probe/distance_probe_asset.h"
#include "engine/math/cube_face.h"

#include <cmath>

namespace specula::test {

struct AnalyticBox {
    glm::vec3 lo{-4.f, -1.2f, -4.f}, hi{4.f, 2.8f, 4.f};

    // Distance from x (inside) along unit d to the wall.
    float exit(glm::vec3 x, glm::vec3 d) const {
        float t = 1e30f;
        for (int i = 0; i < 3; ++i) {
            if (d[i] > 1e-12f) t = std::min(t, (hi[i] - x[i]) / d[i]);
            if (d[i] < -1e-12f) t = std::min(t, (lo[i] - x[i]) / d[i]);
        }
        return t;
    }
    static glm::vec3 radianceAt(glm::vec3 p) {
        return glm::vec3(0.5f + 0.4f * std::sin(1.7f * p.x + 0.3f * p.y),
                         0.5f + 0.4f * std::sin(1.3f * p.z - 0.9f * p.y),
                         0.5f + 0.4f * std::cos(0.8f * p.x + 1.1f * p.z));
    }
    glm::vec3 trace(glm::vec3 x, glm::vec3 d) const { return radianceAt(x + exit(x, d) * d); }
};

// A one-layer (composite only) probe of the box at face resolution n.
inline DistanceProbeAsset makeBoxProbe(const AnalyticBox& box, int n) {
    DistanceProbeAsset a;
    a.faceRes = n;
    a.dInf = 1000.f;
    a.boxMin = box.lo;
    a.boxMax = box.hi;
    float maxD = 0.f, minD = 1e30f;
    DistanceProbeLayer L;
    L.name = "box";
    for (int f = 0; f < 6; ++f) {
        L.faces[std::size_t(f)] = Image(n, n, 4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec2 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                const glm::vec3 d = glm::normalize(glsl::cubeFaceDirection(f, uv));
                const float t = box.exit(glm::vec3(0.f), d);
                const glm::vec3 c = AnalyticBox::radianceAt(t * d);
                float* p = L.faces[std::size_t(f)].at(x, y);
                p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = t;
                maxD = std::max(maxD, t);
                minD = std::min(minD, t);
            }
    }
    L.avgDistance = 4.f;
    L.minDistance = minD;
    L.maxDistance = maxD;
    L.solidAngle = 12.566f;
    a.range = 0.5f * (maxD + 1.f) * 1.05f;
    a.layers.push_back(L);
    return a;
}

} // namespace specula::test
