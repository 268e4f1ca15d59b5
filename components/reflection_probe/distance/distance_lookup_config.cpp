#include "distance_lookup_config.h"

#include "engine/core/error.h"

#include <nlohmann/json.hpp>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace specula {

namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
} // namespace glsl

// The table's shader indices are the GLSL constants.
static_assert(kDistanceMethods[0].glslIndex == glsl::kMethodEnvmap &&
              kDistanceMethods[1].glslIndex == glsl::kMethodBoxProj &&
              kDistanceMethods[2].glslIndex == glsl::kMethodBisection &&
              kDistanceMethods[3].glslIndex == glsl::kMethodSecant &&
              kDistanceMethods[4].glslIndex == glsl::kMethodAvgDist &&
              kDistanceMethods[5].glslIndex == glsl::kMethodMarch);

const DistanceMethodInfo& info(DistanceMethod m) {
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.method == m) return row;
    throw Error("distance method", "", "not in kDistanceMethods");
}

const char* toString(DistanceMethod m) {
    return info(m).label.name;
}

const DistanceMethodInfo* findDistanceMethod(std::string_view name) {
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (name == row.label.name) return &row;
    return nullptr;
}

std::string distanceMethodNames() {
    std::string s;
    for (const DistanceMethodInfo& row : kDistanceMethods)
        s += (s.empty() ? "" : ", ") + std::string(row.label.name);
    return s;
}

std::string distanceFeatureName(std::uint32_t f) {
    std::string s;
    auto add = [&](std::uint32_t bit, const char* name) {
        if (!(f & bit)) return;
        if (!s.empty()) s += '+';
        s += name;
    };
    add(kFeatureLayers, "layers");
    for (const DistanceMethodInfo& row : kDistanceMethods)
        add(row.feature, row.label.name);
    add(kFeatureGlossy, "glossy");
    add(kFeatureFresnel, "fresnel");
    add(kFeatureCompressedComposite, "bc6h");
    return s;
}

namespace {

std::uint32_t featureOfIndex(int glslIndex) {
    for (const DistanceMethodInfo& row : kDistanceMethods)
        if (row.glslIndex == glslIndex) return row.feature;
    return info(DistanceMethod::Envmap).feature;
}

// A layer's method named in the manifest; nullopt unless it is a per-layer row.
const DistanceMethodInfo* perLayerMethod(const std::string& name) {
    const DistanceMethodInfo* row = findDistanceMethod(name);
    return row && row->glslIndex >= 0 ? row : nullptr;
}

} // namespace

int bisectionSteps(float range, float tolerance) {
    const double ratio = 2.0 * double(range) / std::max(double(tolerance), 1e-12);
    if (!(ratio > 1.0)) return 1;
    return int(std::clamp(std::ceil(std::log2(ratio)), 1.0, 40.0));
}

namespace {

DistanceLookupConfig methodConfig(const DistanceProbe& probe, const DistanceProbeAsset& a) {
    const std::string& manifest = a.manifestPath;
    if (a.layers.size() > std::size_t(glsl::kMaxDistanceLayers))
        throw Error(manifest, "layers",
                    "at most " + std::to_string(glsl::kMaxDistanceLayers - 1) +
                        " object layers are supported");
    DistanceLookupConfig c{}; // every unused layer entry and pad zero
    glsl::DistanceParams& p = c.params;
    p.boxMin = a.boxMin;
    p.boxMax = a.boxMax;
    p.centre = a.centre;
    p.faceRes = a.faceRes;
    p.range = probe.range > 0.f ? probe.range : a.range;
    // A range past the sentinel only loses x in x + D l (float) and searches nothing real.
    p.range = std::min(p.range, 0.5f * a.dInf);
    p.tolerance = std::isfinite(probe.errorTolerance) && probe.errorTolerance > 0.f
                      ? probe.errorTolerance
                      : std::numeric_limits<float>::min();
    p.dInf = a.dInf;
    p.maxSteps = bisectionSteps(p.range, p.tolerance);
    for (std::size_t i = 0; i < a.layers.size(); ++i) {
        c.layers[i].avgDistance = a.layers[i].avgDistance;
        c.layers[i].boxMin = a.layers[i].boxMin;
        c.layers[i].boxMax = a.layers[i].boxMax;
    }
    float reach = std::numeric_limits<float>::max();
    for (std::size_t i = a.layers.size(); i-- > 1;) {
        const glm::vec3 closest =
            glm::clamp(glm::vec3(0.f), c.layers[i].boxMin, c.layers[i].boxMax);
        reach = std::min(reach, glm::length(closest));
        c.layers[i].reach = reach;
    }

    if (probe.method == DistanceMethod::Planned) {
        // A measured plan chose d_e with its lookup ("effect_plan": {"lookup": {"tolerance"}});
        // a manifest without one keeps the user's.
        if (!a.effectPlan.empty()) {
            const nlohmann::json plan = nlohmann::json::parse(a.effectPlan, nullptr, false);
            if (plan.is_discarded() || !plan.is_object())
                throw Error(manifest, "effect_plan", "expected a JSON object");
            if (plan.contains("lookup") && plan["lookup"].contains("tolerance")) {
                const nlohmann::json& t = plan["lookup"]["tolerance"];
                if (!t.is_number() || !std::isfinite(t.get<double>()) || t.get<double>() < 0.0)
                    throw Error(manifest, "effect_plan.lookup.tolerance",
                                "expected a finite number >= 0 (metres; 0: the user's d_e)");
                if (t.get<float>() > 0.f) {
                    p.tolerance = t.get<float>();
                    p.maxSteps = bisectionSteps(p.range, p.tolerance);
                }
            }
        }
        // The cooked plan: the composite alone when it baked no object layers, else every
        // baked layer with the method the plan gave it.
        auto planned = [&](std::size_t i) {
            const DistanceMethodInfo* row = perLayerMethod(a.layers[i].method);
            if (!row)
                throw Error(manifest, "layers[" + std::to_string(i) + "].method",
                            "expected envmap, boxproj, bisection, secant, avgdist or march, got '" +
                                a.layers[i].method + "'");
            return row->glslIndex;
        };
        if (a.objectLayerCount() == 0) {
            p.method = planned(0);
            c.features = featureOfIndex(p.method);
            return c;
        }
        p.layerCount = a.objectLayerCount();
        c.features = kFeatureLayers;
        for (int i = 1; i <= p.layerCount; ++i) {
            c.layers[i].method = planned(std::size_t(i));
            c.features |= featureOfIndex(c.layers[i].method);
        }
        return c;
    }
    if (probe.method != DistanceMethod::Layered) {
        p.method = info(probe.method).glslIndex;
        c.features = featureOfIndex(p.method);
        return c;
    }
    if (a.objectLayerCount() < 1)
        throw Error(manifest, "layers", "layered lookup needs at least one object layer");
    p.layerCount = a.objectLayerCount();
    c.features = kFeatureLayers;
    for (int i = 1; i <= p.layerCount; ++i) {
        const DistanceMethodInfo* row = &info(probe.layerMethod);
        if (!row->perLayer) {
            // The cooked plan decides: a layer without a usable plan gets bisection.
            row = perLayerMethod(a.layers[std::size_t(i)].method);
            if (!row || !row->perLayer || row->method == DistanceMethod::Bisection)
                row = &info(DistanceMethod::Bisection);
        }
        c.layers[i].method = row->glslIndex;
        c.features |= row->feature;
    }
    return c;
}

} // namespace

DistanceLookupConfig makeLookupConfig(const DistanceProbe& probe, const DistanceProbeAsset& a) {
    DistanceLookupConfig c = methodConfig(probe, a);
    if (a.compression == DistanceCompression::Bc6h) c.features |= kFeatureCompressedComposite;
    return c;
}

} // namespace specula
