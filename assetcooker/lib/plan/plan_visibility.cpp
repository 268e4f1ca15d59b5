#include "assetcooker/lib/plan/plan_visibility.h"

#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "engine/math/cube_face.h"
#include "engine/raytrace/embree_scene.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace specula {

namespace {

constexpr float kPi = 3.14159265f;

// Bounding sphere of an object's world bounds, relative to `centre`.
struct Sphere {
    glm::vec3 offset;
    float radius;
};
Sphere boundingSphere(const EnvironmentObject& o, glm::vec3 centre) {
    return {o.bounds.centre() - centre, o.bounds.boundingRadius()};
}

} // namespace

CubeTexels::CubeTexels(int faceRes) : n(faceRes) {
    dirs.reserve(std::size_t(6) * n * n);
    solidAngles.reserve(dirs.capacity());
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec2 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                dirs.push_back(glm::normalize(glsl::cubeFaceDirection(f, uv)));
                solidAngles.push_back(float(cubeTexelSolidAngle(x, y, n)));
            }
}

std::vector<std::uint32_t> texelsInCone(const CubeTexels& cube, glm::vec3 axis, float halfAngle) {
    const float cosHalf = std::cos(std::min(halfAngle + 0.5f * kPi / float(cube.n), kPi));
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < cube.size(); ++i)
        if (glm::dot(cube.dirs[i], axis) >= cosHalf) out.push_back(std::uint32_t(i));
    return out;
}

std::vector<char> grownMask(const std::vector<std::uint32_t>& texels, int n, int grow) {
    const std::size_t face = std::size_t(n) * n;
    std::vector<char> mask(6 * face, 0), rows(6 * face, 0);
    for (std::uint32_t t : texels)
        mask[t] = 1;
    if (grow <= 0) return mask;
    // Along x, then along y: the square window is the product of the two intervals. Each
    // pass marks the run [i - grow, i + grow] of every set texel with a difference array.
    auto pass = [&](const std::vector<char>& in, std::vector<char>& out, bool alongX) {
        std::vector<int> diff(std::size_t(n) + 1);
        for (int f = 0; f < 6; ++f)
            for (int line = 0; line < n; ++line) {
                auto at = [&](int i) {
                    return f * face + (alongX ? std::size_t(line) * n + std::size_t(i)
                                              : std::size_t(i) * n + std::size_t(line));
                };
                std::fill(diff.begin(), diff.end(), 0);
                for (int i = 0; i < n; ++i)
                    if (in[at(i)]) {
                        ++diff[std::size_t(std::max(0, i - grow))];
                        --diff[std::size_t(std::min(n, i + grow + 1))];
                    }
                int open = 0;
                for (int i = 0; i < n; ++i) {
                    open += diff[std::size_t(i)];
                    out[at(i)] = open > 0;
                }
            }
    };
    pass(mask, rows, true);
    pass(rows, mask, false);
    return mask;
}

std::vector<ObjectView> viewObjectsFromCentre(ecs::Registry& registry, const SceneMarkup& markup,
                                              glm::vec3 centre, const CubeTexels& cube) {
    std::vector<ObjectView> views(markup.objects.size());
    if (markup.objects.empty()) return views;
    // Which object each mesh entity belongs to, by entity index: the per-ray filter is O(1).
    std::vector<std::uint32_t> owner;
    for (std::size_t i = 0; i < markup.objects.size(); ++i)
        for (ecs::Entity e : markup.objects[i].meshes) {
            if (owner.size() <= e.index) owner.resize(std::size_t(e.index) + 1, UINT32_MAX);
            owner[e.index] = std::uint32_t(i);
        }
    const EmbreeScene scene(registry, [&](ecs::Entity e) {
        return e.index < owner.size() && owner[e.index] != UINT32_MAX;
    });
    tbb::parallel_for(std::size_t(0), markup.objects.size(), [&](std::size_t i) {
        const Sphere s = boundingSphere(markup.objects[i], centre);
        const float dist = glm::length(s.offset);
        // A texel-centre ray can meet the object only inside the cone of its bounding sphere;
        // every texel when the sphere holds the centre.
        std::vector<std::uint32_t> candidates;
        if (dist <= s.radius || !std::isfinite(dist)) {
            candidates.resize(cube.size());
            for (std::size_t t = 0; t < cube.size(); ++t)
                candidates[t] = std::uint32_t(t);
        } else {
            candidates = texelsInCone(cube, s.offset / dist, std::asin(s.radius / dist));
        }
        const EmbreeScene::Filter mine = [&](ecs::Entity e) {
            return e.index < owner.size() && owner[e.index] == i;
        };
        ObjectView& v = views[i];
        double weighted = 0.0, weight = 0.0;
        float nearest = std::numeric_limits<float>::max();
        for (std::uint32_t t : candidates) {
            const auto hit = scene.intersect(centre, cube.dirs[t], 0.f,
                                             std::numeric_limits<float>::infinity(), &mine);
            if (!hit) continue;
            v.texels.push_back(t);
            weighted += double(cube.solidAngles[t]) * hit->t;
            weight += cube.solidAngles[t];
            nearest = std::min(nearest, hit->t);
        }
        v.solidAngle = float(weight);
        v.average = weight > 0 ? float(weighted / weight) : 0.f;
        v.nearest = weight > 0 ? nearest : 0.f;
    });
    return views;
}

} // namespace specula
