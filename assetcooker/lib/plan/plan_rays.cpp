#include "assetcooker/lib/plan/plan_rays.h"

#include "engine/math/orthonormal_frame.h"
#include "engine/raytrace/ground_truth.h"
#include "engine/scene/components.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include <glm/glm.hpp>

namespace specula {

namespace {

constexpr float kPi = 3.14159265f;
constexpr int kDims = 8; // triangle, 2 barycentric, 3 displacement, 2 direction

struct Triangle {
    glm::vec3 p[3];
    glm::vec3 n[3]; // world-space vertex normals (the geometric one where the mesh has none)
};

std::vector<Triangle> reflectorTriangles(ecs::Registry& registry, const SceneMarkup& markup) {
    std::vector<Triangle> out;
    for (const ReflectorMarkup& r : markup.reflectors)
        for (ecs::Entity e : r.meshes) {
            const Mesh* mesh = registry.find<Mesh>(e);
            const Transform* t = registry.find<Transform>(e);
            if (!mesh || !t) continue;
            const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(t->world)));
            for (const Primitive& prim : mesh->primitives) {
                const MeshData& m = *prim.mesh;
                for (std::size_t i = 0; i + 2 < m.indices.size(); i += 3) {
                    Triangle tri;
                    for (int k = 0; k < 3; ++k) {
                        const std::uint32_t v = m.indices[i + std::size_t(k)];
                        tri.p[k] = glm::vec3(t->world * glm::vec4(m.positions[v], 1.f));
                        tri.n[k] =
                            v < m.normals.size() ? normalMatrix * m.normals[v] : glm::vec3(0.f);
                    }
                    const glm::vec3 g = glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]);
                    if (!(glm::dot(g, g) > 0.f)) continue; // degenerate: no area to sample
                    for (glm::vec3& n : tri.n)
                        n = glm::dot(n, n) > 0.f ? glm::normalize(n) : glm::normalize(g);
                    out.push_back(tri);
                }
            }
        }
    return out;
}

// A uniform float in [0, 1) from 24 generator bits: the same on every standard library.
float unitFloat(std::mt19937& rng) {
    return float(rng() >> 8) * (1.f / 16777216.f);
}

// Latin hypercube: in each dimension the n draws fall one per stratum, the strata's order
// permuted independently per dimension; jittered within the stratum.
std::vector<std::array<float, kDims>> latinHypercube(int n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::vector<std::array<float, kDims>> u(static_cast<std::size_t>(n));
    std::vector<int> perm(static_cast<std::size_t>(n));
    for (int d = 0; d < kDims; ++d) {
        std::iota(perm.begin(), perm.end(), 0);
        for (int i = n - 1; i > 0; --i) // Fisher-Yates with our own bounded draw
            std::swap(perm[std::size_t(i)], perm[std::size_t(rng() % std::uint32_t(i + 1))]);
        for (int i = 0; i < n; ++i)
            u[std::size_t(i)][std::size_t(d)] =
                (float(perm[std::size_t(i)]) + unitFloat(rng)) / float(n);
    }
    return u;
}

} // namespace

PlanRaySample samplePlanRays(ecs::Registry& registry, const SceneMarkup& markup,
                             const PlanRayOptions& o) {
    PlanRaySample sample;
    const std::vector<Triangle> tris = reflectorTriangles(registry, markup);
    if (tris.empty() || o.count <= 0) return sample;
    std::vector<double> cdf(tris.size());
    double total = 0.0;
    for (std::size_t i = 0; i < tris.size(); ++i) {
        total += 0.5 * double(glm::length(
                           glm::cross(tris[i].p[1] - tris[i].p[0], tris[i].p[2] - tris[i].p[0])));
        cdf[i] = total;
    }
    sample.area = total;

    TraceOptions topt;
    topt.environmentOnly = true;
    topt.mirrors = markup.mirrorEntities;
    topt.sky = o.sky;
    const GroundTruthTracer tracer(registry, topt);

    const auto u = latinHypercube(o.count, o.seed);
    std::vector<PlanRay> rays(u.size());
    std::vector<char> kept(u.size(), 0);
    tbb::parallel_for(std::size_t(0), u.size(), [&](std::size_t i) {
        const std::array<float, kDims>& s = u[i];
        const double pick = double(s[0]) * total;
        const std::size_t k = std::min<std::size_t>(
            std::size_t(std::lower_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()),
            tris.size() - 1);
        const Triangle& tri = tris[k];
        // Uniform barycentrics (the square folded onto the triangle).
        float b1 = s[1], b2 = s[2];
        if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
        const float b0 = 1.f - b1 - b2;
        glm::vec3 p = b0 * tri.p[0] + b1 * tri.p[1] + b2 * tri.p[2];
        const glm::vec3 n = glm::normalize(b0 * tri.n[0] + b1 * tri.n[1] + b2 * tri.n[2]);
        p += o.cellSize * (glm::vec3(s[3], s[4], s[5]) - 0.5f);
        const glm::vec3 off = p - o.centre;
        const float len = glm::length(off);
        if (len > o.reach && len > 0.f) p = o.centre + off * (o.reach / len);
        // A reflector point the environment hides from the centre has moved through a
        // wall: no player sees it there.
        if (glm::length(p - o.centre) > 1e-4f &&
            tracer.environmentScene().intersect(o.centre, p - o.centre, 1e-4f, 1.f))
            return;
        glm::vec3 dir;
        if (!o.eyes.empty() && float(i) < o.viewShare * float(u.size())) {
            const glm::vec3 eye = o.eyes[i % o.eyes.size()];
            const glm::vec3 v = p - eye;
            // Seen from the eye: facing it, and nothing in between (the reflector's own far
            // side included: a bowl hides its underside).
            if (!(glm::dot(v, n) < 0.f) || tracer.fullScene().intersect(eye, v, 1e-4f, 1.f - 1e-3f))
                return;
            dir = glm::normalize(glm::reflect(glm::normalize(v), n));
        } else {
            // Cosine-weighted about n (Malley: a uniform disc lifted to the hemisphere).
            const float r = std::sqrt(s[6]), phi = 2.f * kPi * s[7];
            const auto [t, b] = orthonormalFrame(n);
            const float z = std::sqrt(std::max(0.f, 1.f - s[6]));
            dir = glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + z * n);
        }
        rays[i] = {p, dir, tracer.traceEnvironment(p, dir).radiance};
        kept[i] = 1;
    });
    for (std::size_t i = 0; i < rays.size(); ++i)
        if (kept[i])
            sample.rays.push_back(rays[i]);
        else
            ++sample.rejected;
    return sample;
}

} // namespace specula
