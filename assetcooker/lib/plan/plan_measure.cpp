#include "assetcooker/lib/plan/plan_measure.h"
#include "assetcooker/lib/os/memory_estimate.h"

#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "components/reflection_probe/distance/distance_compression.h"
#include "engine/core/error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

namespace specula {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string fixed(double v, int digits) {
    if (std::isnan(v)) return "-";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

// JSON has no inf or NaN: those become null.
nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// Whether candidate c is what the analytic plan would run (d_e 0.01: the runtime default).
bool isAnalytic(const PlanCandidate& c, const EffectPlan& a, int faceRes) {
    if (c.faceRes != faceRes) return false;
    if (a.mode == "layered")
        return c.method == "layered" && (c.tolerance == 0.f || c.tolerance == 0.01f);
    const std::string m = a.layers.empty() ? "envmap" : a.layers.front().method;
    if (c.method != m) return false;
    return c.tolerance == 0.f || c.tolerance == 0.01f;
}

} // namespace

MeasuredPlan measurePlan(ecs::Registry& registry, const SceneMarkup& markup,
                         const EffectPlan& analytic, glm::vec3 centre, float reach,
                         const MeasuredPlanOptions& o) {
    const auto start = Clock::now();
    MeasuredPlan m;
    m.budget = o.budget;
    m.model = benchCostModel();
    m.seed = o.seed;
    m.viewShare = o.eyes.empty() ? 0.f : o.viewShare;

    PlanRayOptions ro;
    ro.count = o.rays;
    ro.seed = o.seed;
    ro.centre = centre;
    ro.cellSize = o.cellSize;
    ro.reach = reach;
    ro.sky = o.sky;
    ro.eyes = o.eyes;
    ro.viewShare = o.viewShare;
    const PlanRaySample sample = samplePlanRays(registry, markup, ro);
    m.rays = int(sample.rays.size());
    m.rejected = sample.rejected;
    if (sample.rays.empty()) {
        m.reason = "no reflector ray to measure on: the analytic plan stands";
        m.seconds = secondsSince(start);
        return m;
    }

    // The probes the candidates read: the analytic plan's layers when it has some (the
    // composite-only candidates read their layer 0, the same composite a composite-only bake
    // holds), else the composite alone; at the cook's resolution and half of it.
    const bool layered = analytic.mode == "layered";
    const auto bakeStart = Clock::now();
    auto bake = [&](int res) {
        DistanceBakeOptions b;
        b.centre = centre;
        b.faceRes = res;
        b.sky = o.sky;
        b.reflectorReach = reach;
        b.proxy = o.proxy;
        applyPlan(analytic, b);
        b.faceRes = res;
        if (!layered) b.compositeOnly = true;
        return bakeDistanceProbe(registry, markup, b);
    };
    // Both probes are held at once: refused up front, not after the first (minutes) is baked.
    const std::uint64_t layers = layered ? 1 + analytic.layers.size() : 1;
    checkMemoryFor(cubeLayersBytes(o.faceRes, layers) + cubeLayersBytes(o.faceRes / 2, layers),
                   "the measured plan at face_res " + std::to_string(o.faceRes) + " and " +
                       std::to_string(o.faceRes / 2) + " with " + std::to_string(layers) +
                       " layers",
                   "", "face_res");
    // Below 16^2 faces half the resolution is no probe worth weighing: one resolution.
    const DistanceProbeAsset full = bake(o.faceRes);
    const DistanceProbeAsset half = o.faceRes >= 16 ? bake(o.faceRes / 2) : full;
    m.bakeSeconds = secondsSince(bakeStart);

    m.candidates = candidateSet(full, half, layered);
    for (PlanCandidate& c : m.candidates)
        c.analytic = isAnalytic(c, analytic, o.faceRes);
    applyPlanFormats(m.candidates, o.formats);
    // The compressed copies the BC6H candidates read (about a second a 256^2 cube); one
    // resolution weighed, one copy.
    std::optional<DistanceProbeAsset> fullBc6h, halfBc6h;
    if (o.formats != PlanFormats::Float) {
        fullBc6h = full;
        compressComposite(*fullBc6h);
        if (half.faceRes != full.faceRes) {
            halfBc6h = half;
            compressComposite(*halfBc6h);
        }
    }
    const PlanAssets assets{full, half, fullBc6h ? &*fullBc6h : nullptr,
                            halfBc6h ? &*halfBc6h : nullptr};
    scoreCandidates(m.candidates, assets, sample.rays, m.model);
    m.noiseMeasured = o.measureNoise;
    if (o.measureNoise) {
        std::vector<PlanCandidate> again = m.candidates;
        ro.seed = o.seed + 1;
        const PlanRaySample other = samplePlanRays(registry, markup, ro);
        scoreCandidates(again, assets, other.rays, m.model);
        auto best = [](const std::vector<PlanCandidate>& cs) {
            double b = -std::numeric_limits<double>::infinity();
            for (const PlanCandidate& c : cs)
                if (c.measured()) b = std::max(b, c.psnr);
            return b;
        };
        const double bestA = best(m.candidates), bestB = best(again);
        for (std::size_t i = 0; i < again.size(); ++i) {
            const double a = m.candidates[i].psnr, b = again[i].psnr;
            // Past 60 dB the error is float rounding (a sky read exactly), not sampling.
            if (!std::isfinite(a) || !std::isfinite(b) || a > 60.0 || b > 60.0) continue;
            m.noiseDb = std::max(m.noiseDb, std::abs(a - b));
            if (bestA <= 60.0 && bestB <= 60.0)
                m.noiseGapDb = std::max(m.noiseGapDb, std::abs((a - bestA) - (b - bestB)));
        }
    }
    m.maxMibPerProbe = o.maxMibPerProbe;
    m.winner = choosePlanCandidate(m.candidates, m.budget, m.reason, m.warning, m.maxMibPerProbe);
    m.seconds = secondsSince(start);
    return m;
}

PlanFormats planFormatsFor(bool compress, double maxMibPerProbe) {
    if (compress) return PlanFormats::Bc6h;
    return maxMibPerProbe > 0.0 ? PlanFormats::FloatAndBc6h : PlanFormats::Float;
}

std::vector<glm::vec3> sceneEyes(const ProbeScene& scene) {
    try {
        return {sceneCameraView(scene, 1024, 768).eye()}; // the bench's frame
    } catch (const Error&) {
        return {}; // no camera and no view to place: the hemisphere alone
    }
}

EffectPlan applyMeasurement(const EffectPlan& analytic, const MeasuredPlan& measured) {
    EffectPlan p = analytic;
    p.measurement = measured.toJson();
    p.measurementText = measured.toText();
    const PlanCandidate* w = measured.chosen();
    if (!w) return p;
    p.faceRes = w->faceRes;
    p.lookupMethod = w->method;
    p.lookupTolerance = w->tolerance;
    p.compressed = w->compressed;
    const std::string why = "measured: " + w->label() + ", " + measured.reason;
    if (w->method == "layered") {
        p.mode = "layered";
        p.modeReason = why;
    } else {
        p.mode = w->method == "envmap" ? "envmap" : "single";
        p.modeReason = why;
        PlannedLayer composite{"composite", {}, w->method, "every object in the composite"};
        for (const PlannedObject& o : analytic.objects)
            if (o.decision != "invisible") composite.objects.push_back(o.name);
        p.layers = {composite};
    }
    p.features = planFeatures(p);
    return p;
}

nlohmann::json MeasuredPlan::toJson() const {
    nlohmann::json j;
    j["rays"] = rays;
    j["rejected_rays"] = rejected;
    j["seed"] = seed;
    j["view_share"] = viewShare;
    j["sampling_noise_db"] = noiseMeasured ? number(noiseDb) : nlohmann::json(nullptr);
    j["sampling_noise_gap_db"] = noiseMeasured ? number(noiseGapDb) : nlohmann::json(nullptr);
    j["budget"] = budget.text();
    j["budget_source"] = budget.source;
    j["cost_model"] = {{"c0", model.c0},
                       {"c_fetch", model.c1},
                       {"c_layer", model.c2},
                       {"rows", model.rows},
                       {"rms_residual", model.rmsResidual},
                       {"max_residual", model.maxResidual},
                       {"source", model.source}};
    j["candidates"] = nlohmann::json::array();
    for (const PlanCandidate& c : candidates)
        j["candidates"].push_back({{"method", c.method},
                                   {"tolerance", c.tolerance},
                                   {"face_res", c.faceRes},
                                   {"object_layers", c.objectLayers},
                                   {"compressed", c.compressed},
                                   {"psnr_db", number(c.psnr)},
                                   {"rmse", number(c.rmse)},
                                   {"fetches", number(c.fetches)},
                                   {"mib", c.mib},
                                   {"cost_x_envmap", number(c.cost)},
                                   {"meets", c.meets},
                                   {"analytic", c.analytic},
                                   {"note", c.note}});
    if (maxMibPerProbe > 0.0) j["max_mib_per_probe"] = maxMibPerProbe;
    j["winner"] = winner;
    j["reason"] = reason;
    if (!warning.empty()) j["warning"] = warning;
    // No times: a cooked folder's bytes depend on its inputs only (shard_bake.h).
    return j;
}

std::string MeasuredPlan::toText() const {
    std::ostringstream s;
    s << "measured on " << rays << " reflector rays (seed " << seed << ", "
      << int(viewShare * 100.f + 0.5f) << " % of the draws reflecting the scene camera's view; "
      << rejected << " draws dropped: hidden from the centre, or from the camera)\n";
    if (noiseMeasured)
        s << "sampling noise  " << fixed(noiseDb, 2) << " dB on a PSNR, " << fixed(noiseGapDb, 2)
          << " dB on a gap to the best (largest change with seed " << seed + 1 << ")\n";
    else
        s << "sampling noise  not measured (specula-cook plan measures it)\n";
    s << "cost model  " << model.text() << "\n";
    s << "budget  "
      << (budget.kind == ErrorBudget::Kind::None ? "none: within 0.5 dB of the best"
                                                 : budget.text() + " (" + budget.source + ")")
      << "\n";
    if (maxMibPerProbe > 0.0)
        s << "memory  at most " << fixed(maxMibPerProbe, 1) << " MiB per probe\n";
    char line[256];
    std::snprintf(line, sizeof line, "  %-26s %8s %8s %8s %6s %8s %9s  %s\n", "candidate",
                  "PSNR dB", "RMSE", "fetches", "layers", "MiB", "x envmap", "");
    s << line;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
        const PlanCandidate& c = candidates[i];
        std::string flags = c.meets ? "meets" : "";
        if (c.analytic) flags += flags.empty() ? "analytic" : ", analytic";
        if (int(i) == winner) flags = "WINNER" + (flags.empty() ? "" : ", " + flags);
        if (!c.note.empty()) flags += (flags.empty() ? "" : "; ") + c.note;
        std::snprintf(line, sizeof line, "  %-26s %8s %8s %8s %6d %8.1f %9s  %s\n",
                      c.label().c_str(), fixed(c.psnr, 2).c_str(), fixed(c.rmse, 4).c_str(),
                      fixed(c.fetches, 2).c_str(), c.objectLayers, c.mib, fixed(c.cost, 2).c_str(),
                      flags.c_str());
        s << line;
    }
    if (!warning.empty()) s << "warning  " << warning << "\n";
    s << "chosen  " << (chosen() ? chosen()->label() : std::string("(none)")) << "  (" << reason
      << ")\n";
    s << "plan time  " << fixed(seconds, 2) << " s (probes baked in " << fixed(bakeSeconds, 2)
      << " s)\n";
    return s.str();
}

} // namespace specula
