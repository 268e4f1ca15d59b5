#include "assetcooker/lib/plan/effect_plan.h"

#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "assetcooker/lib/plan/plan_layer_packing.h"
#include "assetcooker/lib/plan/plan_visibility.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "engine/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include <glm/glm.hpp>

namespace specula {

namespace {

constexpr float kPi = 3.14159265f;

std::string fmt(float v, int digits = 2) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
}

// The runtime binds the composite and at most this many object layers.
constexpr std::size_t kMaxObjectLayers = std::size_t(glsl::kMaxDistanceLayers - 1);

} // namespace

EffectPlan planEffects(ecs::Registry& registry, const SceneMarkup& markup, glm::vec3 centre,
                       float reach, PlanThresholds t, int markupProbe) {
    EffectPlan plan;
    // The user's needs, from the markup of the probe being planned.
    std::optional<std::string> forcedFlavour;
    std::optional<bool> forcedFresnel, forcedBackground;
    if (markupProbe >= 0 && markupProbe < int(markup.probes.size())) {
        const ProbeMarkup& probe = markup.probes[std::size_t(markupProbe)];
        const nlohmann::json& o = probe.options;
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
                throw Error(probe.node, "specula_probe.flavour",
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

    // Visibility from the probe centre, each object on its own, at low resolution.
    const CubeTexels cube(t.analysisFaceRes);
    const std::vector<ObjectView> views = viewObjectsFromCentre(registry, markup, centre, cube);

    const float tolRad = t.maxErrorDeg * kPi / 180.f;
    // Rough reflectors (plan_glossy.h): the sharpest one's lobe decides, and only where it is
    // wider than the tolerance; below it the plan is a mirror's, to the letter.
    const SharpestLobe lobe = planReflectors(markup, plan.reflectors);
    plan.lobeDeg = lobe.deg;
    const float lobeRad = lobe.deg * kPi / 180.f;
    const bool lobeHides = lobeRad > tolRad;
    plan.lobeReason =
        lobe.text + (!(lobe.deg > 0.f) ? ""
                     : lobeHides       ? ": wider than the " + fmt(t.maxErrorDeg) +
                                       " deg tolerance, parallax below it hides in the blur"
                                 : ": no wider than the " + fmt(t.maxErrorDeg) +
                                       " deg tolerance, planned as a mirror");
    const float texelAngle = 0.5f * kPi / float(t.analysisFaceRes);
    // Near objects overlap where their grown coverage shares a texel. Per texel, the nearest
    // near object given the average distance and the farthest near object are all the
    // occlusion test needs: O(objects x texels), where comparing every pair was quadratic.
    struct TexelDepths {
        int objects = 0;
        float nearestAvgdist = std::numeric_limits<float>::infinity();
        float farthest = -std::numeric_limits<float>::infinity();
    };
    std::vector<TexelDepths> texels(cube.size());
    struct Near {
        std::size_t object;
        std::vector<std::uint32_t> texels; // its grown coverage (layer packing)
    };
    std::vector<Near> nears;
    std::vector<std::string> distant;
    int blurred = 0; // objects the lobe's blur made distant
    for (std::size_t i = 0; i < views.size(); ++i) {
        const ObjectView& L = views[i];
        const EnvironmentObject& o = markup.objects[i];
        PlannedObject po;
        po.name = o.name;
        po.nearest = L.nearest;
        po.average = L.average;
        po.solidAngle = L.solidAngle;
        std::vector<std::uint32_t> cone;
        if (L.solidAngle <= 0.f) {
            // Smaller than the analysis texels (or hidden from the centre): judge it by its
            // bounding sphere instead, which errs on the side of correcting it.
            const glm::vec3 mid = o.bounds.centre() - centre;
            const float radius = o.bounds.boundingRadius();
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
            cone = texelsInCone(cube, glm::normalize(mid), halfAngle);
        }
        // From a reflector point up to `reach` off the centre, the direction to the object's
        // nearest point turns by at most asin(reach / nearest): the direction-only error.
        const float parallax = reach >= po.nearest ? 0.5f * kPi : std::asin(reach / po.nearest);
        po.parallaxDeg = parallax * 180.f / kPi;
        if (parallax < tolRad) {
            po.decision = "distant";
            po.reason = "direction-only error <= " + fmt(po.parallaxDeg) + " deg < " +
                        fmt(t.maxErrorDeg) + " deg at " + fmt(po.nearest) + " m";
            distant.push_back(o.name);
        } else if (lobeHides && parallax < lobeRad) {
            po.decision = "distant";
            po.reason = "parallax up to " + fmt(po.parallaxDeg, 1) + " deg at " + fmt(po.nearest) +
                        " m < " + lobe.text +
                        ": the blur hides it -> direction-only lookup of "
                        "the prefiltered chain";
            distant.push_back(o.name);
            ++blurred;
        } else {
            po.decision = po.solidAngle >= t.rectifySolidAngle ? "rectify" : "avgdist";
            po.reason = "parallax up to " + fmt(po.parallaxDeg, 1) + " deg; covers " +
                        fmt(po.solidAngle, 3) + " sr " + (po.decision == "rectify" ? ">= " : "< ") +
                        fmt(t.rectifySolidAngle, 3) + " sr -> " +
                        (po.decision == "rectify" ? "per-pixel rectification" : "average distance");
            const int grow = int(std::ceil(parallax / texelAngle));
            std::vector<char> mask = grownMask(L.texels, t.analysisFaceRes, grow);
            for (std::uint32_t k : cone)
                mask[k] = 1;
            std::vector<std::uint32_t> covered;
            for (std::size_t k = 0; k < mask.size(); ++k) {
                if (!mask[k]) continue;
                covered.push_back(std::uint32_t(k));
                TexelDepths& d = texels[k];
                ++d.objects;
                d.farthest = std::max(d.farthest, po.nearest);
                if (po.decision == "avgdist")
                    d.nearestAvgdist = std::min(d.nearestAvgdist, po.nearest);
            }
            nears.push_back({plan.objects.size(), std::move(covered)});
        }
        plan.objects.push_back(po);
    }

    // Near to far. Where objects can overlap (as seen from some reflector point) occlusion
    // can show in the reflection, so each keeps a layer of its own: with tight per-layer
    // bounds a ray that misses an object skips its layer without a fetch, which is cheaper
    // than merging objects into wide layers every ray must search.
    std::stable_sort(nears.begin(), nears.end(), [&](const Near& a, const Near& b) {
        return plan.objects[a.object].nearest < plan.objects[b.object].nearest;
    });
    bool anyOverlap = false;
    float occluderParallax = 0.f; // widest band a small occluder can uncover, degrees
    for (const TexelDepths& d : texels) {
        if (d.objects < 2) continue;
        anyOverlap = true;
        // What a small occluder uncovers as the reflector moves by `reach`: its parallax
        // relative to what lies behind it, reach (1/d_front - 1/d_back); widest for the
        // nearest small occluder in front of the farthest object sharing the texel.
        if (d.farthest > d.nearestAvgdist)
            occluderParallax =
                std::max(occluderParallax,
                         reach * (1.f / d.nearestAvgdist - 1.f / d.farthest) * 180.f / kPi);
    }
    if (nears.size() <= kMaxObjectLayers) {
        for (const Near& n : nears) {
            const PlannedObject& po = plan.objects[n.object];
            const bool rectify = po.decision == "rectify";
            plan.layers.push_back({po.name,
                                   {po.name},
                                   rectify ? "bisection" : "avgdist",
                                   rectify ? "large: per-pixel rectification"
                                           : "small: one fetch at its average distance"});
        }
    } else {
        // More near objects than the runtime binds layers: those that never overlap as seen
        // from the cell share a layer (plan_layer_packing.h), each at its own distance, so a
        // shared layer is rectified per pixel.
        std::vector<std::vector<std::uint32_t>> coverage;
        for (Near& n : nears)
            coverage.push_back(std::move(n.texels));
        const LayerPacking packing = packNearObjects(coverage, cube.size(), kMaxObjectLayers);
        for (std::size_t l = 0; l < packing.layers.size(); ++l) {
            const std::vector<std::size_t>& members = packing.layers[l];
            PlannedLayer layer{"packed_" + std::to_string(l + 1), {}, "bisection", ""};
            for (const std::size_t m : members)
                layer.objects.push_back(plan.objects[nears[m].object].name);
            if (members.size() == 1) {
                const bool rectify = plan.objects[nears[members[0]].object].decision == "rectify";
                layer.name = layer.objects[0];
                layer.method = rectify ? "bisection" : "avgdist";
                layer.reason = rectify ? "large: per-pixel rectification"
                                       : "small: one fetch at its average distance";
            } else {
                layer.reason = std::to_string(members.size()) + " objects packed (" +
                               std::to_string(nears.size()) + " near objects, at most " +
                               std::to_string(kMaxObjectLayers) +
                               " object layers): each at its own distance, rectified per pixel";
            }
            plan.layers.push_back(std::move(layer));
        }
        plan.layerPacking = std::to_string(nears.size()) + " near objects packed into " +
                            std::to_string(packing.layers.size()) +
                            " object layers; objects in one layer never overlap as seen from "
                            "the cell";
        if (packing.forced > 0)
            plan.layerPacking += ", except " + std::to_string(packing.forced) +
                                 " placed past the cap where they overlap least (" +
                                 std::to_string(packing.forcedTexels) +
                                 " analysis texels: occlusion there as seen from the centre)";
    }
    if (!distant.empty())
        plan.layers.push_back(
            {"distant", distant, "envmap",
             blurred ? "far enough, or blurred enough by the lobe, for the direction-only lookup"
                     : "far enough for the direction-only lookup"});

    // Mode: the cheapest runtime path that represents the plan.
    if (nears.empty()) {
        plan.mode = "envmap";
        plan.modeReason = markup.objects.empty() ? "no environment geometry: only the distant sky"
                          : blurred ? "every object is distant or its parallax hides in the blur "
                                      "of the sharpest reflector's lobe"
                                    : "every object is distant";
    } else if (!anyOverlap || (lobeHides && occluderParallax < lobe.deg)) {
        plan.mode = "single";
        plan.modeReason =
            !anyOverlap ? "no two near objects overlap as seen from the cell: one layer, merged"
                        : "near objects overlap, but occluders uncover at most " +
                              fmt(occluderParallax, 1) + " deg behind them < " + lobe.text +
                              ": the blur hides the occlusion, one layer, merged";
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
        if (!plan.layerPacking.empty()) plan.modeReason += " (" + plan.layerPacking + ")";
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
    } else if (occluderParallax > 30.f && lobeHides && occluderParallax < lobe.deg) {
        plan.flavour = "distance";
        plan.flavourReason = "a small occluder can uncover " + fmt(occluderParallax, 1) +
                             " deg of what is behind it, < " + lobe.text +
                             ": the blur hides the disocclusion, a distance cube map serves";
    } else if (occluderParallax > 30.f) {
        plan.flavour = "lightfield";
        plan.flavourReason = "a small occluder can uncover " + fmt(occluderParallax, 1) +
                             " deg of what is behind it: disocclusions a distance cube map "
                             "cannot show";
    } else {
        plan.flavour = "distance";
        const std::string uncovered =
            "occluders uncover at most " + fmt(occluderParallax, 1) + " deg behind them";
        plan.flavourReason =
            !anyOverlap ? "no occlusion parallax to represent"
            : plan.mode == "layered"
                ? uncovered + ": layered distance cube maps represent the occlusion"
                : uncovered + ", hidden in the lobe's blur: one distance cube map "
                              "serves";
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

    plan.features = planFeatures(plan);
    return plan;
}

std::string planFeatures(const EffectPlan& plan) {
    // Named by the distance flavour's method table.
    std::uint32_t bits = plan.mode == "layered" ? kFeatureLayers : 0;
    if (plan.mode == "envmap") bits |= info(DistanceMethod::Envmap).feature;
    for (const PlannedLayer& l : plan.layers)
        if (const DistanceMethodInfo* row = findDistanceMethod(l.method)) bits |= row->feature;
    if (plan.fresnel) bits |= kFeatureFresnel;
    return distanceFeatureName(bits);
}

void applyPlan(const EffectPlan& plan, DistanceBakeOptions& bake) {
    if (plan.faceRes > 0) bake.faceRes = plan.faceRes;
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
    j["reflectors"] = nlohmann::json::array();
    for (const PlannedReflector& r : reflectors)
        j["reflectors"].push_back(
            {{"name", r.name}, {"roughness", r.roughness}, {"lobe_half_width_deg", r.lobeDeg}});
    j["lobe"] = {{"half_width_deg", lobeDeg}, {"reason", lobeReason}};
    j["user_needs"] = userNeeds;
    j["features"] = features;
    if (!lookupMethod.empty())
        j["lookup"] = {{"method", lookupMethod},
                       {"tolerance", lookupTolerance},
                       {"face_res", faceRes},
                       {"compression", compressed ? "bc6h" : "none"}};
    if (!measurement.is_null()) j["measured"] = measurement;
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
    if (std::any_of(reflectors.begin(), reflectors.end(),
                    [](const PlannedReflector& r) { return r.roughness > 0.f; }))
        s << "lobe     " << fmt(lobeDeg, 1) << " deg  (" << lobeReason << ")\n";
    for (const PlannedReflector& r : reflectors)
        if (r.roughness > 0.f)
            s << "reflector  " << r.name << ": roughness " << fmt(r.roughness) << ", lobe "
              << fmt(r.lobeDeg, 1) << " deg\n";
    for (const std::string& n : userNeeds)
        s << "user need  " << n << "\n";
    s << "objects:\n";
    for (const PlannedObject& o : objects)
        s << "  " << o.name << ": " << o.decision << " - " << o.reason << "\n";
    if (!lookupMethod.empty())
        s << "lookup   " << lookupMethod << ", d_e "
          << (lookupTolerance > 0.f ? fmt(lookupTolerance, 3) : "-") << ", faces " << faceRes
          << "^2\n";
    s << measurementText;
    return s.str();
}

} // namespace specula
