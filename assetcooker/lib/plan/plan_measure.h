#pragma once
// The measured effect plan (issue 15): instead of trusting thresholds tuned on the bundled
// scenes, the cooker bakes the few probes the candidates need, scores every runtime
// configuration with the CPU twin against Embree on a stratified sample of reflector rays
// (plan_rays.h), predicts each one's cost from the bench-calibrated model (plan_cost.h) and
// keeps the cheapest that meets the error budget (plan_candidates.h). The analytic plan
// (effect_plan.h) still proposes the layer grouping and is the fallback.
#include "assetcooker/lib/plan/effect_plan.h"
#include "assetcooker/lib/plan/plan_candidates.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace specula {

struct MeasuredPlanOptions {
    int faceRes = 256; // the cook's; candidates also weigh half of it
    int rays = 32768;  // sampling noise about 0.3-0.6 dB on the bundled scenes (two seeds)
    std::uint32_t seed = 1;
    // Scores the candidates on a second sample too (seed + 1) and reports the largest PSNR
    // difference between the two: the sampling noise the choice must be read against.
    bool measureNoise = true;
    ErrorBudget budget; // kind None: the cheapest within kNoBudgetSlackDb of the best
    const Image* sky = nullptr;
    float cellSize = 1.5f;
    std::optional<Aabb> proxy;
    std::vector<glm::vec3> eyes; // view points (plan_rays.h); empty: the hemisphere alone
    float viewShare = 0.f;
    // The memory budget (--max-mib-per-probe): candidates whose textures take more are left
    // out (choosePlanCandidate). 0: none.
    double maxMibPerProbe = 0.0;
    // The composite's formats weighed (plan_candidates.h): the cook weighs BC6H beside float
    // under a memory budget, and BC6H alone when --compress bc6h asks for it.
    PlanFormats formats = PlanFormats::Float;
};

// The formats a plan weighs for a cook: BC6H alone when the user compresses, float and BC6H
// under a memory budget (the plan picks the format), else float.
PlanFormats planFormatsFor(bool compress, double maxMibPerProbe);

// The view points of a scene (its camera node, else the default view the sandbox and bench
// place; empty when it has neither) and the share of rays a plan gives them by default:
// half, the views the scene states; the other half over the hemisphere, the views it does
// not.
inline constexpr float kDefaultViewShare = 0.5f;
struct ProbeScene;
std::vector<glm::vec3> sceneEyes(const ProbeScene& scene);

struct MeasuredPlan {
    std::vector<PlanCandidate> candidates;
    int winner = -1; // index into candidates; -1: no reflector ray (the analytic plan stands)
    std::string reason, warning;
    ErrorBudget budget;
    double maxMibPerProbe = 0.0; // 0: no memory budget
    CostModel model;
    int rays = 0, rejected = 0;
    std::uint32_t seed = 1;
    float viewShare = 0.f; // the share of draws from the scene camera
    bool noiseMeasured = false;
    double noiseDb = 0.0;     // largest |PSNR(seed) - PSNR(seed + 1)| over the candidates
    double noiseGapDb = 0.0;  // the same for each candidate's gap to the best PSNR
    double bakeSeconds = 0.0; // the candidates' probes
    double seconds = 0.0;     // the whole measurement

    const PlanCandidate* chosen() const {
        return winner >= 0 ? &candidates[std::size_t(winner)] : nullptr;
    }
    nlohmann::json toJson() const;
    std::string toText() const;
};

// Measures the candidates around `analytic` (whose layered grouping, when it has one, is the
// layered candidates'). Needs updateWorldTransforms first.
MeasuredPlan measurePlan(ecs::Registry& registry, const SceneMarkup& markup,
                         const EffectPlan& analytic, glm::vec3 centre, float reach,
                         const MeasuredPlanOptions& options);

// The analytic plan with the measured winner applied: mode, layers and methods, face
// resolution and lookup (method and d_e) as chosen, the measurement attached. Without a
// winner, `analytic` unchanged but for the measurement.
EffectPlan applyMeasurement(const EffectPlan& analytic, const MeasuredPlan& measured);

} // namespace specula
