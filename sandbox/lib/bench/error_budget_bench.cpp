// The bench's side of the error budget: which rows get one, the extra bake, the log lines.
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/core/error.h"
#include "sandbox/lib/bench/bench_internal.h"
#include "sandbox/lib/walk/probe_source.h"

#include <chrono>
#include <cmath>
#include <cstdio>

namespace specula {

namespace {

// Layered's search term is that of the per-layer methods the cooked plan chose (the average
// distance for small layers): the same lookup with bisection on every layer, on the twin,
// says how much of it a setting recovers without touching the shader.
void logEveryLayerBisection(const std::vector<BudgetRay>& rays, const MethodVariant& v,
                            const DistanceProbeAsset& asset, const MethodErrorBudget& planned,
                            std::ostream& log) {
    DistanceProbe settings = v.distance;
    settings.layerMethod = DistanceMethod::Bisection;
    const MethodErrorBudget b = measureErrorBudget(rays, settings, asset, nullptr);
    char line[240];
    std::snprintf(line, sizeof line,
                  "  %s budget layered %s, bisection on every layer: %.2f dB (the plan's "
                  "layer methods: %.2f dB; exact search: %.2f dB)\n",
                  planned.scene.c_str(), v.params.c_str(), psnrOfMse(b.base),
                  psnrOfMse(planned.base), psnrOfMse(b.exact));
    log << line << std::flush;
}

} // namespace

void appendErrorBudgets(ReflectionScene& scene, const CameraView& cam, const BenchTruth& truth,
                        const std::string& sceneName, const std::string& probeDir, int faceRes,
                        bool progress, const std::vector<MethodVariant>& variants,
                        const std::vector<BenchRow>& rows, std::vector<MethodErrorBudget>& budgets,
                        std::ostream& log) {
    const auto t0 = std::chrono::steady_clock::now();
    const DistanceProbeAsset asset = readDistanceProbe(probeDir + "/manifest.json");
    DistanceProbeAsset asset2x;
    std::string note;
    if (2 * faceRes <= kBudgetMaxFaceRes) {
        log << sceneName << ": baking the budget's distance probe (" << 2 * faceRes << "^2 faces)\n"
            << std::flush;
        bakeDistanceProbeInto(scene, probeDir + "_2x", 2 * faceRes, progress, false, &log);
        asset2x = readDistanceProbe(probeDir + "_2x/manifest.json");
    } else {
        note = "faces 2x per side would be " + std::to_string(2 * faceRes) + "^2, over the " +
               std::to_string(kBudgetMaxFaceRes) + "^2 the budget bakes (the bake grows 4x)";
        log << sceneName << ": error budget without the resolution term: " << note << "\n";
    }
    const std::vector<BudgetRay> rays =
        traceBudgetRays(scene, cam, truth.mask, truth.env.color, asset.centre);
    const std::string d01 = formatTolerance(0.01f);
    const StoredProbeVariants stored = storedProbeVariants(asset); // once for every method
    for (const MethodVariant& v : variants) {
        if (v.kind != VariantKind::Probe || v.lightField >= 0 || v.planned) continue;
        if (v.params != "-" && v.params != d01) continue;
        MethodErrorBudget b;
        try {
            b = measureErrorBudget(rays, v.distance, asset, note.empty() ? &asset2x : nullptr,
                                   &stored);
        } catch (const Error& e) {
            log << "  " << sceneName << " budget " << v.method << ": skipped (" << e.what()
                << ")\n";
            continue;
        }
        b.scene = sceneName, b.method = v.method, b.params = v.params, b.res2xNote = note;
        for (const BenchRow& r : rows)
            if (r.scene == sceneName && r.method == v.method && r.params == v.params)
                b.gpuMse = r.rmse * r.rmse;
        char line[320];
        std::snprintf(
            line, sizeof line,
            "  %s budget %s %s: base %.2f dB (GPU %.2f), search %+.2f, resolution "
            "%+.2f, silhouettes %+.2f, disocclusion %+.2f dB; residual %.3g of base (%s), "
            "dominant %s\n",
            sceneName.c_str(), v.method.c_str(), v.params.c_str(), psnrOfMse(b.base),
            psnrOfMse(b.gpuMse), psnrOfMse(b.exact) - psnrOfMse(b.base),
            psnrOfMse(b.res2x) - psnrOfMse(b.base), psnrOfMse(b.sameSurface) - psnrOfMse(b.base),
            psnrOfMse(b.seen) - psnrOfMse(b.base), b.residual / b.base, b.residualSet.c_str(),
            b.dominant().c_str());
        log << line << std::flush;
        if (v.distance.method == DistanceMethod::Layered)
            logEveryLayerBisection(rays, v, asset, b, log);
        budgets.push_back(std::move(b));
    }
    log << sceneName << ": error budget over " << rays.size() << " rays in "
        << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
}

} // namespace specula
