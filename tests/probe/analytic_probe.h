#pragma once
// Closed-form distance probes for tests: the environment is an axis-aligned box (probe-local)
// whose surface radiance is a smooth function of position, so the exact reflection of any
// ray is known without a renderer.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/math/cube_face.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

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

// One layer's six faces baked from the probe centre at face resolution n: `surface(dir)`
// gives the distance along the unit direction (>= dInf where nothing is hit, stored as
// dInf) and the radiance there. Sets minDistance/maxDistance over the texels that hit.
template <typename Surface>
inline DistanceProbeLayer bakeAnalyticLayer(const std::string& name, int n, float dInf,
                                            Surface surface) {
    DistanceProbeLayer L;
    L.name = name;
    L.minDistance = 1e30f;
    for (int f = 0; f < 6; ++f) {
        L.faces[std::size_t(f)] = Image(n, n, 4);
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec2 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                const glm::vec3 d = glm::normalize(glsl::cubeFaceDirection(f, uv));
                const auto [t, c] = surface(d);
                float* p = L.faces[std::size_t(f)].at(x, y);
                p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = std::min(t, dInf);
                if (t >= dInf) continue;
                L.maxDistance = std::max(L.maxDistance, t);
                L.minDistance = std::min(L.minDistance, t);
            }
    }
    return L;
}

// A one-layer (composite only) probe of the box at face resolution n.
inline DistanceProbeAsset makeBoxProbe(const AnalyticBox& box, int n) {
    DistanceProbeAsset a;
    a.faceRes = n;
    a.dInf = 1000.f;
    a.boxMin = box.lo;
    a.boxMax = box.hi;
    DistanceProbeLayer L = bakeAnalyticLayer("box", n, a.dInf, [&](glm::vec3 d) {
        const float t = box.exit(glm::vec3(0.f), d);
        return std::pair(t, AnalyticBox::radianceAt(t * d));
    });
    const float maxD = L.maxDistance;
    L.avgDistance = 4.f;
    L.solidAngle = 12.566f;
    a.range = 0.5f * (maxD + 1.f) * 1.05f;
    a.layers.push_back(L);
    return a;
}

} // namespace specula::test
