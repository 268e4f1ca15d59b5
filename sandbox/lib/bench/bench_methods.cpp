#include "sandbox/lib/bench/bench_methods.h"

#include "components/reflection_probe/lightfield/lightfield_probe.h"
#include "components/reflection_probe/pem/pem_probe.h"

#include <cstdio>

namespace specula {

std::vector<MethodLabel> sandboxMethods() {
    std::vector<MethodLabel> labels;
    for (const DistanceMethodInfo& row : kDistanceMethods)
        labels.push_back(row.label);
    labels.push_back(kLightFieldMethod);
    for (const PemMethodInfo& row : kPemMethods)
        labels.push_back(row.label);
    return labels;
}

std::string formatTolerance(float de) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "d_e=%g", double(de));
    return buf;
}

std::vector<MethodVariant> benchVariants(const BenchSweep& sweep) {
    std::vector<MethodVariant> rows;
    // One row per distance method of the table, one per d_e where its accuracy depends on it.
    for (const DistanceMethodInfo& info : kDistanceMethods) {
        auto add = [&](std::string params, float de) {
            MethodVariant v;
            v.method = info.label.name;
            v.params = std::move(params);
            v.distance.method = info.method;
            v.distance.errorTolerance = de;
            // Layered: every object layer uses the cooked plan's method (bisection for large
            // layers, average distance for small ones) at this d_e.
            v.distance.layerMethod = DistanceMethod::Envmap;
            // The effect plan's choice comes from its own bake (only the layers it keeps).
            v.planned = info.method == DistanceMethod::Planned;
            rows.push_back(std::move(v));
        };
        if (!info.usesTolerance) {
            add("-", 0.01f);
            continue;
        }
        // The measured plan records its own d_e in the manifest, which the lookup takes over
        // the row's: one row, whatever the sweep.
        if (info.method == DistanceMethod::Planned) {
            add("measured", 0.01f);
            continue;
        }
        for (float de : sweep.tolerances)
            add(formatTolerance(de), de);
    }

    // The light field: its accuracy parameters are the cooked sizes (cameras, pixels), one
    // asset per row, with the cooked per-slab disparity.
    for (std::size_t i = 0; i < sweep.lightFields.size(); ++i) {
        MethodVariant v;
        v.method = kLightFieldMethod.name;
        v.params = sweep.lightFields[i];
        v.lightField = int(i);
        rows.push_back(std::move(v));
    }

    MethodVariant gt;
    gt.method = "groundtruth";
    gt.params = "embree";
    gt.kind = VariantKind::GroundTruth;
    rows.push_back(std::move(gt));
    return rows;
}

} // namespace specula
