#include "distance_lookup_config.h"

#include "engine/core/error.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace specula {

const char* toString(LookupMethod m) {
    switch (m) {
    case LookupMethod::Envmap:
        return "envmap";
    case LookupMethod::BoxProj:
        return "boxproj";
    case LookupMethod::Bisection:
        return "bisection";
    case LookupMethod::Secant:
        return "secant";
    case LookupMethod::AvgDist:
        return "avgdist";
    case LookupMethod::Layered:
        return "layered";
    case LookupMethod::Planned:
        return "plan";
    case LookupMethod::LightField:
        return "lightfield";
    }
    return "?";
}

bool parseLookupMethod(const std::string& s, LookupMethod& out) {
    for (LookupMethod m : {LookupMethod::Envmap, LookupMethod::BoxProj, LookupMethod::Bisection,
                           LookupMethod::Secant, LookupMethod::AvgDist, LookupMethod::Layered,
                           LookupMethod::Planned, LookupMethod::LightField}) {
        if (s == toString(m)) {
            out = m;
            return true;
        }
    }
    return false;
}

int methodIndex(LookupMethod m) {
    switch (m) {
    case LookupMethod::Envmap:
        return 0;
    case LookupMethod::BoxProj:
        return 1;
    case LookupMethod::Bisection:
        return 2;
    case LookupMethod::Secant:
        return 3;
    case LookupMethod::AvgDist:
        return 4;
    case LookupMethod::Layered:
        return -1;
    case LookupMethod::Planned:
        return -1;
    case LookupMethod::LightField:
        return -1;
    }
    return 0;
}

static std::uint32_t featureOf(int method) {
    switch (method) {
    case 1:
        return kFeatureBoxProj;
    case 2:
        return kFeatureBisection;
    case 3:
        return kFeatureSecant;
    case 4:
        return kFeatureAvgDist;
    default:
        return kFeatureEnvmap;
    }
}

int bisectionSteps(float range, float tolerance) {
    const double ratio = 2.0 * double(range) / std::max(double(tolerance), 1e-12);
    if (!(ratio > 1.0)) return 1;
    return int(std::clamp(std::ceil(std::log2(ratio)), 1.0, 40.0));
}

DistanceLookupConfig makeLookupConfig(const ReflectionProbe& probe, const DistanceProbeAsset& a) {
    if (a.layers.size() > std::size_t(glsl::kMaxDistanceLayers))
        throw Error(probe.asset, "layers",
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

    if (probe.method == LookupMethod::Planned) {
        // The cooked plan: the composite alone when it baked no object layers, else every
        // baked layer with the method the plan gave it.
        auto planned = [&](std::size_t i) {
            LookupMethod m = LookupMethod::Bisection;
            if (!parseLookupMethod(a.layers[i].method, m) || m == LookupMethod::Layered ||
                m == LookupMethod::Planned)
                throw Error(probe.asset, "layers[" + std::to_string(i) + "].method",
                            "expected envmap, boxproj, bisection, secant or avgdist, got '" +
                                a.layers[i].method + "'");
            return methodIndex(m);
        };
        if (a.objectLayerCount() == 0) {
            p.method = planned(0);
            c.features = featureOf(p.method);
            return c;
        }
        p.layerCount = a.objectLayerCount();
        c.features = kFeatureLayers;
        for (int i = 1; i <= p.layerCount; ++i) {
            c.layers[i].method = planned(std::size_t(i));
            c.features |= featureOf(c.layers[i].method);
        }
        return c;
    }
    if (probe.method != LookupMethod::Layered) {
        p.method = methodIndex(probe.method);
        c.features = featureOf(p.method);
        return c;
    }
    if (a.objectLayerCount() < 1)
        throw Error(probe.asset, "layers", "layered lookup needs at least one object layer");
    p.layerCount = a.objectLayerCount();
    c.features = kFeatureLayers;
    for (int i = 1; i <= p.layerCount; ++i) {
        LookupMethod m = probe.layerMethod;
        if (m == LookupMethod::Envmap || m == LookupMethod::BoxProj || m == LookupMethod::Layered) {
            // The cooked plan decides: a layer without a usable plan gets bisection.
            if (!parseLookupMethod(a.layers[std::size_t(i)].method, m) ||
                (m != LookupMethod::AvgDist && m != LookupMethod::Secant))
                m = LookupMethod::Bisection;
        }
        c.layers[i].method = methodIndex(m);
        c.features |= featureOf(methodIndex(m));
    }
    return c;
}

} // namespace specula
