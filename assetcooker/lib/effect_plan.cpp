#include "effect_plan.h"

#include "assetcooker/lib/distance_bake.h"
#include "engine/core/error.h"
#include "engine/math/cube_face.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace specula {

namespace {

constexpr float kPi = 3.14159265f;

// Which texels of the analysis cube an object covers, grown by `grow` texels within each
// face (a conservative stand-in for the parallax a moving reflector adds).
std::vector<char> coverage(const DistanceProbeLayer& L, float dInf, int grow) {
    const int n = L.faces[0].width;
    std::vector<char> mask(std::size_t(6) * n * n, 0);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                if (L.faces[std::size_t(f)].at(x, y)[3] >= 0.5f * dInf) continue;
                for (int yy = std::max(0, y - grow); yy <= std::min(n - 1, y + grow); ++yy)
                    for (int xx = std::max(0, x - grow); xx <= std::min(n - 1, x + grow); ++xx)
                        mask[(std::size_t(f) * n + yy) * n + xx] = 1;
            }
    return mask;
}

// Texels whose centre direction lies within `halfAngle` of `axis` (a bounding cone).
std::vector<char> coneCoverage(glm::vec3 axis, float halfAngle, int n) {
    std::vector<char> mask(std::size_t(6) * n * n, 0);
    const float cosHalf = std::cos(std::min(halfAngle + 0.5f * kPi / float(n), kPi));
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::vec2 uv((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n));
                const glm::vec3 d = glm::normalize(glsl::cubeFaceDirection(f, uv));
                if (glm::dot(d, axis) >= cosHalf) mask[(std::size_t(f) * n + y) * n + x] = 1;
            }
    return mask;
}

bool overlaps(const std::vector<char>& a, const std::vector<char>& b) {
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i] && b[i]) return true;
    return false;
}

std::string fmt(float v, int digits = 2) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
}

} // namespace

EffectPlan planEffects(ecs::Registry& registry, const SceneMarkup& markup, glm::vec3 centre,
                       float reach, PlanThresholds t) {
    EffectPlan plan;
    // The user's needs, from the probe markup.
    std::optional<std::string> forcedFlavour;
    std::optional<bool> forcedFresnel, forcedBackground;
    if (!markup.probes.empty()) {
        const nlohmann::json& o = markup.probes.front().options;
        if (o.contains("max_error_deg") && o["max_error_deg"].is_number()) {
            t.maxErrorDeg = std::clamp(o["max_error_deg"].get<float>(), 1e-3f, 45.f);
            plan.userNeeds.push_back("max_error_deg = " + fmt(t.maxErrorDeg, 3));
        }
        if (o.contains("motion_range") && o["motion_range"].is_number()) {
            const float range = std::clamp(o["motion_range"].get<float>(), 0.f, 1e4f);
            reach = std::max(reach, 0.5f * std::sqrt(3.f) * range);
            plan.userNeeds.push_back("motion_range = " + fmt(range) + " m");
        }
        if (o.contains("flavour") && o["flavour"].is_string()) {
            forcedFlavour = o["flavour"].get<std::string>();
            if (*forcedFlavour != "distance" && *forcedFlavour != "lightfield")
                throw Error(markup.probes.front().node, "specula_probe.flavour",
                            "expected \"distance\" or \"lightfield\"");
            plan.userNeeds.push_back("flavour = " + *forcedFlavour);
        }
        if (o.contains("fresnel") && o["fresnel"].is_boolean()) {
            forcedFresnel = o["fresnel"].get<bool>();
            plan.userNeeds.push_back(std::string("fresnel = ") +
                                     (*forcedFresnel ? "true" : "false"));
        }
        if (o.contains("background") && o["background"].is_boolean()) {
            forcedBackground = o["background"].get<bool>();
            plan.userNeeds.push_back(std::string("background = ") +
                                     (*forcedBackground ? "true" : "false"));
        }
    }

    // Visibility from the probe centre, one layer per object, at low resolution.
    DistanceBakeOptions bo;
    bo.centre = centre;
    bo.faceRes = t.analysisFaceRes;
    bo.reflectorReach = reach;
    bo.withSky = false;
    for (const EnvironmentObject& o : markup.objects)
        bo.layers.push_back({o.name, {o.name}, "-"});
    DistanceProbeAsset analysis;
    if (!markup.objects.empty()) analysis = bakeDistanceProbe(registry, markup, bo);

    const float tolRad = t.maxErrorDeg * kPi / 180.f;
    const float texelAngle = 0.5f * kPi / float(t.analysisFaceRes);
    struct Near {
        std::size_t object;
        std::vector<char> mask;
    };
    std::vector<Near> nears;
    std::vector<std::string> distant;
    for (std::size_t i = 1; i < analysis.layers.size(); ++i) {
        const DistanceProbeLayer& L = analysis.layers[i];
        PlannedObject po;
        po.name = L.name;
        po.nearest = L.minDistance;
        po.average = L.avgDistance;
        po.solidAngle = L.solidAngle;
        std::vector<char> cone;
        if (L.solidAngle <= 0.f) {
            // Smaller than the analysis texels (or hidden from the centre): judge it by its
            // bounding sphere instead, which errs on the side of correcting it.
            const EnvironmentObject& o =
                *std::find_if(markup.objects.begin(), markup.objects.end(),
                              [&](const EnvironmentObject& e) { return e.name == L.name; });
            const glm::vec3 mid = 0.5f * (o.boundsMin + o.boundsMax) - centre;
            const float radius = 0.5f * glm::length(o.boundsMax - o.boundsMin);
            const float dist = glm::length(mid);
            if (dist <= radius) {
                po.decision = "invisible";
                po.reason = "encloses the probe centre yet no ray from it meets the object";
                plan.objects.push_back(po);
                continue;
            }
            const float halfAngle = std::asin(radius / dist);
            po.nearest = dist - radius;
            po.average = dist;
            po.solidAngle = 2.f * kPi * (1.f - std::cos(halfAngle));
            cone = coneCoverage(glm::normalize(mid), halfAngle, t.analysisFaceRes);
        }
        // From a reflector point up to `reach` off the centre, the direction to the object's
        // nearest point turns by at most asin(reach / nearest): the direction-only error.
        const float parallax = reach >= po.nearest ? 0.5f * kPi : std::asin(reach / po.nearest);
        po.parallaxDeg = parallax * 180.f / kPi;
        if (parallax < tolRad) {
            po.decision = "distant";
            po.reason = "direction-only error <= " + fmt(po.parallaxDeg) + " deg < " +
                        fmt(t.maxErrorDeg) + " deg at " + fmt(po.nearest) + " m";
            distant.push_back(L.name);
        } else {
            po.decision = po.solidAngle >= t.rectifySolidAngle ? "rectify" : "avgdist";
            po.reason = "parallax up to " + fmt(po.parallaxDeg, 1) + " deg; covers " +
                        fmt(po.solidAngle, 3) + " sr " + (po.decision == "rectify" ? ">= " : "< ") +
                        fmt(t.rectifySolidAngle, 3) + " sr -> " +
                        (po.decision == "rectify" ? "per-pixel rectification" : "average distance");
            const int grow = int(std::ceil(parallax / texelAngle));
            std::vector<char> mask = coverage(L, analysis.dInf, grow);
            for (std::size_t k = 0; k < cone.size(); ++k)
                mask[k] |= cone[k];
            nears.push_back({plan.objects.size(), std::move(mask)});
        }
        plan.objects.push_back(po);
    }

    // Near to far. Where objects can overlap (as seen from some reflector point) occlusion
    // can show in the reflection, so each keeps a layer of its own: with tight per-layer
    // bounds a ray that misses an object skips its layer without a fetch, which is cheaper
    // than merging objects into wide layers every ray must search.
    std::sort(nears.begin(), nears.end(), [&](const Near& a, const Near& b) {
        return plan.objects[a.object].nearest < plan.objects[b.object].nearest;
    });
    bool anyOverlap = false;
    float occluderParallax = 0.f; // widest band a small occluder can uncover, degrees
    for (std::size_t i = 0; i < nears.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (overlaps(nears[i].mask, nears[j].mask)) {
                anyOverlap = true;
                // What a small occluder uncovers as the reflector moves by `reach`: its
                // parallax relative to what lies behind it, reach (1/d_front - 1/d_back).
                const PlannedObject& front = plan.objects[nears[j].object];
                const PlannedObject& back = plan.objects[nears[i].object];
                if (front.decision == "avgdist" && back.nearest > front.nearest) {
                    const float uncovered =
                        reach * (1.f / front.nearest - 1.f / back.nearest) * 180.f / kPi;
                    occluderParallax = std::max(occluderParallax, uncovered);
                }
            }
    for (const Near& n : nears) {
        const PlannedObject& po = plan.objects[n.object];
        const bool rectify = po.decision == "rectify";
        plan.layers.push_back({po.name,
                               {po.name},
                               rectify ? "bisection" : "avgdist",
                               rectify ? "large: per-pixel rectification"
                                       : "small: one fetch at its average distance"});
    }
    if (!distant.empty())
        plan.layers.push_back(
            {"distant", distant, "envmap", "far enough for the direction-only lookup"});

    // Mode: the cheapest runtime path that represents the plan.
    if (nears.empty()) {
        plan.mode = "envmap";
        plan.modeReason = markup.objects.empty() ? "no environment geometry: only the distant sky"
                                                 : "every object is distant";
    } else if (!anyOverlap) {
        plan.mode = "single";
        plan.modeReason = "no two near objects overlap as seen from the cell: one layer, merged";
        const bool rectify =
            std::any_of(plan.layers.begin(), plan.layers.end(),
                        [](const PlannedLayer& l) { return l.method == "bisection"; });
        PlannedLayer merged{"composite",
                            {},
                            rectify ? "bisection" : "avgdist",
                            "all objects merged into the composite"};
        for (const PlannedLayer& l : plan.layers)
            merged.objects.insert(merged.objects.end(), l.objects.begin(), l.objects.end());
        if (!distant.empty())
            merged.reason += "; distant objects ride along in the same lookup at no extra fetch";
        plan.layers = {merged};
    } else {
        plan.mode = "layered";
        plan.modeReason = "near objects overlap as seen from the cell: occlusion can show in "
                          "the reflection, so they get their own layers, near to far";
    }

    // Flavour: the light field only for near occluding geometry the distance cube cannot
    // represent (Wang et al. 2012: surfaces hidden from the probe centre but seen from the
    // reflector). Enclosing surfaces (floor, walls) hide nothing; a small object in front of
    // another uncovers a band of it as the reflector moves. Past 30 degrees (a third of a
    // cube face) the layered cube map would show that band as seen from the centre: wrong
    // over a large part of the reflection.
    if (forcedFlavour) {
        plan.flavour = *forcedFlavour;
        plan.flavourReason = "the user asked for it (specula_probe.flavour)";
    } else if (occluderParallax > 30.f) {
        plan.flavour = "lightfield";
        plan.flavourReason = "a small occluder can uncover " + fmt(occluderParallax, 1) +
                             " deg of what is behind it: disocclusions a distance cube map "
                             "cannot show";
    } else {
        plan.flavour = "distance";
        plan.flavourReason = anyOverlap ? "occluders uncover at most " + fmt(occluderParallax, 1) +
                                              " deg behind them: layered distance cube maps "
                                              "represent the occlusion"
                                        : "no occlusion parallax to represent";
    }

    // Fresnel only where a reflector's material asks for an F0 below 1, or the user does.
    std::vector<std::string> asking;
    for (const ReflectorMarkup& r : markup.reflectors)
        if (r.f0 >= 0.f && r.f0 < 1.f) asking.push_back(r.node + " (F0 " + fmt(r.f0, 3) + ")");
    if (forcedFresnel) {
        plan.fresnel = *forcedFresnel;
        plan.fresnelReason = "the user said so (specula_probe.fresnel)";
    } else {
        plan.fresnel = !asking.empty();
        std::string who;
        for (const std::string& a : asking) {
            if (!who.empty()) who += ", ";
            who += a;
        }
        plan.fresnelReason =
            asking.empty() ? "every reflector is a perfect mirror" : "asked for by " + who;
    }
    plan.lightFieldBackground = forcedBackground.value_or(false);
    plan.backgroundReason =
        forcedBackground ? "the user said so (specula_probe.background)" : "not asked for";

    std::vector<std::string> f;
    if (plan.mode == "layered") f.push_back("layers");
    for (const char* m : {"envmap", "bisection", "avgdist"})
        if (std::any_of(plan.layers.begin(), plan.layers.end(),
                        [&](const PlannedLayer& l) { return l.method == m; }) ||
            (plan.mode == "envmap" && std::string(m) == "envmap"))
            f.push_back(m);
    if (plan.fresnel) f.push_back("fresnel");
    for (const std::string& name : f) {
        if (!plan.features.empty()) plan.features += '+';
        plan.features += name;
    }
    return plan;
}

void applyPlan(const EffectPlan& plan, DistanceBakeOptions& bake) {
    bake.layers.clear();
    if (plan.mode == "layered") {
        for (const PlannedLayer& l : plan.layers)
            bake.layers.push_back({l.name, l.objects, l.method});
        bake.compositeOnly = false;
    } else {
        bake.compositeOnly = true;
        bake.compositeMethod = plan.layers.empty() ? "envmap" : plan.layers.front().method;
    }
}

nlohmann::json EffectPlan::toJson() const {
    nlohmann::json j;
    j["flavour"] = {{"value", flavour}, {"reason", flavourReason}};
    j["mode"] = {{"value", mode}, {"reason", modeReason}};
    j["layers"] = nlohmann::json::array();
    for (const PlannedLayer& l : layers)
        j["layers"].push_back(
            {{"name", l.name}, {"objects", l.objects}, {"method", l.method}, {"reason", l.reason}});
    j["fresnel"] = {{"value", fresnel}, {"reason", fresnelReason}};
    j["lightfield_background"] = {{"value", lightFieldBackground}, {"reason", backgroundReason}};
    j["objects"] = nlohmann::json::array();
    for (const PlannedObject& o : objects)
        j["objects"].push_back({{"name", o.name},
                                {"nearest_m", o.nearest},
                                {"average_m", o.average},
                                {"solid_angle_sr", o.solidAngle},
                                {"parallax_deg", o.parallaxDeg},
                                {"decision", o.decision},
                                {"reason", o.reason}});
    j["user_needs"] = userNeeds;
    j["features"] = features;
    return j;
}

std::string EffectPlan::toText() const {
    std::ostringstream s;
    s << "flavour  " << flavour << "  (" << flavourReason << ")\n";
    s << "mode     " << mode << "  (" << modeReason << ")\n";
    s << "shader   " << features << "\n";
    for (std::size_t i = 0; i < layers.size(); ++i) {
        s << "layer " << i + 1 << "  " << layers[i].method << "  [";
        for (std::size_t k = 0; k < layers[i].objects.size(); ++k)
            s << (k ? ", " : "") << layers[i].objects[k];
        s << "]  (" << layers[i].reason << ")\n";
    }
    s << "fresnel  " << (fresnel ? "on" : "off") << "  (" << fresnelReason << ")\n";
    s << "background from light field  " << (lightFieldBackground ? "on" : "off") << "  ("
      << backgroundReason << ")\n";
    for (const std::string& n : userNeeds)
        s << "user need  " << n << "\n";
    s << "objects:\n";
    for (const PlannedObject& o : objects)
        s << "  " << o.name << ": " << o.decision << " - " << o.reason << "\n";
    return s.str();
}

} // namespace specula
