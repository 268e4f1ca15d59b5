#include "assetcooker/lib/scene/probe_sanity.h"

#include "engine/core/error.h"
#include "engine/raytrace/embree_scene.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <unordered_map>

#include <glm/glm.hpp>

namespace specula {

namespace {

// Fibonacci sphere: n directions of near-equal solid angle, deterministic.
glm::vec3 spreadDirection(int i, int n) {
    const float golden = 2.39996323f; // pi (3 - sqrt 5)
    const float y = 1.f - 2.f * (float(i) + 0.5f) / float(n);
    const float r = std::sqrt(std::max(0.f, 1.f - y * y));
    const float phi = golden * float(i);
    return glm::vec3(r * std::cos(phi), y, r * std::sin(phi));
}

std::string percent(double share) {
    char b[32];
    std::snprintf(b, sizeof b, "%.0f %%", 100.0 * share);
    return b;
}

std::string metres(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.3g m", std::abs(v)); // never "-0 m"
    return b;
}

// Who the probe is, for messages: its markup node when it sits there, else the centre.
std::string probeField(const SceneMarkup& markup, glm::vec3 centre) {
    for (const ProbeMarkup& p : markup.probes)
        if (p.position == centre) return "nodes[" + p.node + "].extras.specula_probe";
    char b[96];
    std::snprintf(b, sizeof b, "probe centre (%g, %g, %g)", double(centre.x), double(centre.y),
                  double(centre.z));
    return b;
}

} // namespace

ProbePlacement measureProbePlacement(ecs::Registry& registry, const SceneMarkup& markup,
                                     glm::vec3 centre, int directions) {
    ProbePlacement m;
    m.directions = directions;
    std::unordered_map<std::uint32_t, std::size_t> objectOf; // mesh entity index -> object
    Aabb bounds;
    for (std::size_t i = 0; i < markup.objects.size(); ++i) {
        for (ecs::Entity e : markup.objects[i].meshes)
            objectOf[e.index] = i;
        bounds.extend(markup.objects[i].bounds);
    }
    const EmbreeScene scene(registry,
                            [&](ecs::Entity e) { return !markup.mirrorEntities.count(e); });
    m.geometry = !scene.empty();
    if (!markup.objects.empty()) {
        m.sceneSize = glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
        m.outside = bounds.distance(centre);
    }
    if (!m.geometry) return m;

    struct Sample {
        float t = -1.f; // < 0: no hit
        bool back = false;
        std::size_t object = 0;
    };
    std::vector<Sample> samples(static_cast<std::size_t>(directions));
    tbb::parallel_for(0, directions, [&](int i) {
        const glm::vec3 dir = spreadDirection(i, directions);
        const auto hit = scene.intersect(centre, dir, 0.f);
        if (!hit) return;
        Sample& s = samples[std::size_t(i)];
        s.t = hit->t;
        const bool doubleSided =
            hit->primitive && hit->primitive->material && hit->primitive->material->doubleSided;
        s.back = !doubleSided && glm::dot(hit->geometricNormal, dir) > 0.f;
        const auto it = objectOf.find(hit->entity.index);
        s.object = it != objectOf.end() ? it->second : markup.objects.size();
    });
    std::map<std::size_t, int> backByObject;
    m.nearest = std::numeric_limits<float>::max();
    float farthest = 0.f;
    for (const Sample& s : samples) {
        if (s.t < 0.f) continue;
        ++m.hits;
        m.nearest = std::min(m.nearest, s.t);
        farthest = std::max(farthest, s.t);
        if (s.back) ++m.backHits, ++backByObject[s.object];
    }
    if (m.hits == 0) m.nearest = 0.f;
    if (m.hits > 0) m.sceneSize = 2.0 * double(farthest);
    // Small far objects can slip between the spread directions: aim at each one too, so that
    // "nothing to reflect" means degenerate or absent geometry, not sparse sampling.
    if (m.hits == 0)
        for (const EnvironmentObject& o : markup.objects) {
            const glm::vec3 to = o.bounds.centre() - centre;
            if (glm::dot(to, to) > 0.f && scene.intersect(centre, to, 0.f)) ++m.aimedHits;
        }
    const auto most =
        std::max_element(backByObject.begin(), backByObject.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    if (most != backByObject.end() && most->first < markup.objects.size())
        m.backObject = markup.objects[most->first].name;
    return m;
}

std::vector<std::string> checkProbePlacement(ecs::Registry& registry, const SceneMarkup& markup,
                                             glm::vec3 centre, bool hasSky) {
    const ProbePlacement m = measureProbePlacement(registry, markup, centre);
    const std::string field = probeField(markup, centre);
    std::vector<std::string> warnings;
    if (m.hits == 0 && m.aimedHits == 0) {
        const std::string none = "none of " + std::to_string(m.directions) +
                                 " directions from the probe, nor a ray aimed at each of its " +
                                 std::to_string(markup.objects.size()) +
                                 " objects, meets environment geometry (degenerate or zero-sized)";
        if (!hasSky)
            throw Error("", field,
                        "nothing to reflect: " +
                            (m.geometry ? none : "the scene has no environment geometry") +
                            " and there is no sky panorama");
        if (m.geometry) warnings.push_back(field + ": " + none + ": the probe holds the sky alone");
        return warnings;
    }
    if (m.hits == 0) {
        warnings.push_back(field + ": environment geometry covers under 1/" +
                           std::to_string(m.directions) +
                           " of the view (only rays aimed at its objects meet it): the probe "
                           "holds " +
                           (hasSky ? "the sky" : "black") + " almost everywhere");
        return warnings;
    }
    const double back = double(m.backHits) / double(m.hits);
    const std::string backText =
        "sees back faces" + (m.backObject.empty() ? "" : " of '" + m.backObject + "'") + " in " +
        percent(back) + " of the " + std::to_string(m.hits) + " directions that meet geometry";
    if (back > 0.5)
        throw Error("", field,
                    backText + ": it is inside a solid, or outside a closed room looking at the "
                               "backs of its walls");
    if (back >= 0.1)
        warnings.push_back(field + ": " + backText +
                           " (single-sided geometry seen from behind; mark it doubleSided if "
                           "that is meant)");
    // Float resolves about 6e-8 of a coordinate's magnitude; a hit closer than 1e-6 of the
    // scene's size is on the surface as far as the bake can tell.
    const double scale = std::max({m.sceneSize, double(glm::length(glm::dvec3(centre))), 1e-30});
    if (m.nearest <= 1e-6 * scale)
        throw Error("", field,
                    "lies on a surface: the nearest environment hit is " + metres(m.nearest) +
                        " away (scene size " + metres(m.sceneSize) +
                        "), and zero distances cannot be baked; move the probe off it");
    if (m.nearest < 1e-3 * m.sceneSize)
        warnings.push_back(field + ": the nearest environment surface is only " +
                           metres(m.nearest) + " away (scene size " + metres(m.sceneSize) +
                           "): half of what the probe sees is that surface");
    const double seen = double(m.hits) / double(m.directions);
    if (m.outside > 0.f && seen < 0.25)
        warnings.push_back(field + ": lies " + metres(m.outside) +
                           " outside the bounds of all environment geometry and meets it in " +
                           "only " + percent(seen) + " of directions");
    return warnings;
}

} // namespace specula
