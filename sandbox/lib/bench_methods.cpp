#include "bench_methods.h"

#include <cstdio>

namespace specula {

bool parseSandboxMethod(const std::string& s, LookupMethod& out) {
    return parseLookupMethod(s, out);
}

std::string formatTolerance(float de) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "d_e=%g", double(de));
    return buf;
}

std::vector<MethodVariant> benchVariants(const BenchSweep& sweep) {
    std::vector<MethodVariant> rows;
    auto add = [&](LookupMethod m, std::string params, float de) {
        MethodVariant v;
        v.method = toString(m);
        v.params = std::move(params);
        v.probe.method = m;
        v.probe.errorTolerance = de;
        // Layered: every object layer uses the cooked plan's method (bisection for large
        // layers, average distance for small ones) at this d_e.
        v.probe.layerMethod = LookupMethod::Envmap;
        rows.push_back(std::move(v));
        return &rows.back();
    };
    add(LookupMethod::Envmap, "-", 0.01f);
    add(LookupMethod::BoxProj, "-", 0.01f);
    for (LookupMethod m : {LookupMethod::Bisection, LookupMethod::Secant})
        for (float de : sweep.tolerances)
            add(m, formatTolerance(de), de);
    add(LookupMethod::AvgDist, "-", 0.01f);
    for (float de : sweep.tolerances)
        add(LookupMethod::Layered, formatTolerance(de), de);
    // The effect plan's choice, from its own bake (only the layers the plan keeps).
    for (float de : sweep.tolerances)
        add(LookupMethod::Planned, formatTolerance(de), de)->planned = true;

    // The light field: its accuracy parameters are the cooked sizes (cameras, pixels), one
    // asset per row, with the cooked per-slab disparity.
    for (std::size_t i = 0; i < sweep.lightFields.size(); ++i) {
        MethodVariant* v = add(LookupMethod::LightField, sweep.lightFields[i], 0.01f);
        v->probe.flavour = ProbeFlavour::LightFieldSlab;
        v->lightField = int(i);
    }

    MethodVariant gt;
    gt.method = "groundtruth";
    gt.params = "embree";
    gt.kind = VariantKind::GroundTruth;
    rows.push_back(std::move(gt));
    return rows;
}

} // namespace specula
