#pragma once
// The effect plan: which reflection effects a probe needs, decided from the scene and
// explained. A scene pays for exactly what it needs: distant objects are looked up by
// direction only, large near ones are rectified per pixel, small near ones get the average
// distance, layers exist only where objects can occlude each other in a reflection, and
// Fresnel only where a material asks. Rough reflectors blur what they reflect: where the
// sharpest reflector's GGX lobe is wider than the parallax a lookup would correct, the cheaper
// lookup serves (plan_glossy.h: the rule and its geometry). The user can state needs in the probe
// node's extras
// ("specula_probe": {"max_error_deg", "motion_range", "flavour", "fresnel"}); the plan
// honours them and says so.
#include "assetcooker/lib/plan/plan_glossy.h"
#include "assetcooker/lib/scene/scene_markup.h"
#include "engine/ecs/registry.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace specula {

struct PlanThresholds {
    // Largest angular error (degrees) the direction-only lookup may make anywhere in the
    // reflector cell before an object needs correcting.
    float maxErrorDeg = 1.0f;
    // Solid angle from which an object is rectified per pixel rather than given the average
    // distance: a cone of 20 degrees half-angle, 2 pi (1 - cos 20 deg) = 0.379 sr. Within such
    // a cone a flat surface's distance varies by less than 1/cos(20 deg) - 1 = 6.4 % of its
    // nearest distance, which the single d-bar fetch absorbs; wider, it does not.
    float rectifySolidAngle = 0.379f;
    int analysisFaceRes = 32; // resolution of the visibility analysis from the probe centre
};

struct PlannedObject {
    std::string name;
    float nearest = 0.f, average = 0.f, solidAngle = 0.f, parallaxDeg = 0.f;
    std::string decision; // "distant", "rectify", "avgdist", "invisible"
    std::string reason;
};

struct PlannedLayer {
    std::string name;
    std::vector<std::string> objects;
    std::string method; // bisection, avgdist, envmap
    std::string reason;
};

struct EffectPlan {
    std::string flavour; // "distance" or "lightfield"
    std::string flavourReason;
    std::string mode; // "envmap" (direction only), "single" (one rectified layer), "layered"
    std::string modeReason;
    std::vector<PlannedLayer> layers; // near to far; the distant layer last
    // Set when more near objects than the runtime's object layers were packed into shared
    // layers (plan_layer_packing.h): how many, into how many, and what that cost.
    std::string layerPacking;
    bool fresnel = false;
    std::string fresnelReason;
    bool lightFieldBackground = false;
    std::string backgroundReason;
    std::vector<PlannedObject> objects;
    // Every reflector with its lobe; the sharpest (narrowest) lobe is the one the plan weighs.
    std::vector<PlannedReflector> reflectors;
    float lobeDeg = 0.f; // the sharpest reflector's lobe half-width, degrees (0: a mirror)
    std::string lobeReason;
    std::vector<std::string> userNeeds; // what the markup asked for, as read
    std::string features;               // shader features the plan compiles in
    // Set by a measured plan (plan_measure.h): the face resolution to bake (0: the cook's),
    // the lookup chosen and its d_e (written as "lookup" and read at run time by the Planned
    // method; 0: the user's d_e), and the measurement itself (its candidates and the choice).
    int faceRes = 0;
    std::string lookupMethod;
    float lookupTolerance = 0.f;
    bool compressed = false; // the composite in BC6H (written as "lookup": {"compression"})
    nlohmann::json measurement;
    std::string measurementText;

    nlohmann::json toJson() const;
    std::string toText() const;
};

struct DistanceBakeOptions;
// Makes `bake` follow the plan: the plan's layers and methods when layered, else the
// composite alone with the plan's single method (nothing else is baked or uploaded); the
// plan's face resolution when it states one.
void applyPlan(const EffectPlan& plan, DistanceBakeOptions& bake);

// The shader variant a plan compiles (its mode, its layers' methods, Fresnel), by name.
std::string planFeatures(const EffectPlan& plan);

// Analyses the environment from `centre` (a low-resolution visibility bake) with reflector
// points anywhere within `reach` of it. Markup needs override `thresholds`. Cost: one BVH of
// the environment, per object the rays of the analysis texels inside its bounding cone, and
// the occlusion test per texel: O(objects x analysis texels), linear in the node count (20,000
// nodes plan in about a second; tests/bench/plan_bench.cpp).
// `markupProbe`: the `specula_probe` node (index into markup.probes) whose members state
// the user's needs (a level plans each probe with its own; -1: a probe no node holds).
EffectPlan planEffects(ecs::Registry& registry, const SceneMarkup& markup, glm::vec3 centre,
                       float reach, PlanThresholds thresholds = {}, int markupProbe = 0);

} // namespace specula
