#pragma once
// The runtime configurations a measured plan weighs, and how each one is scored: the CPU twin
// of the shader (CpuDistanceProbe) on the plan's rays against their Embree truth, its
// fetches counted, its cost predicted (plan_cost.h), and the choice between them.
#include "assetcooker/lib/plan/plan_budget.h"
#include "assetcooker/lib/plan/plan_cost.h"
#include "assetcooker/lib/plan/plan_rays.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"

#include <string>
#include <vector>

namespace specula {

struct PlanCandidate {
    std::string method;    // envmap, boxproj, avgdist, bisection, secant, march, layered
    float tolerance = 0.f; // d_e, metres; 0 where the method does not search
    int faceRes = 0;
    int objectLayers = 0; // baked and uploaded object layers (0: the composite alone)
    // The composite stored compressed (`--compress bc6h`: BC6H radiance, R16F or R32F
    // distance), scored on the compressed copy of its probe: what the format costs in accuracy.
    bool compressed = false;
    bool analytic = false; // what the analytic plan would run
    // Measured on the rays (NaN when the configuration could not run; `note` says why).
    double psnr = 0.0, rmse = 0.0, fetches = 0.0;
    double mib = 0.0;  // GPU texels: the cube maps the configuration uploads, and the sky
    double cost = 0.0; // predicted pass time, x envmap
    bool meets = false;
    std::string note;

    std::string label() const; // "secant d_e=0.03 256^2", "... 256^2 bc6h"
    bool measured() const { return !std::isnan(rmse); }
};

// The candidate set over two assets baked with the same layers at the cook's resolution and
// half of it (`full`, `half`; `layered`: whether their object layers are the analytic plan's
// grouping worth weighing). Deterministic order: resolution, then envmap, boxproj, avgdist,
// bisection, secant, march (d_e 0.1, 0.03, 0.01), layered.
std::vector<PlanCandidate> candidateSet(const DistanceProbeAsset& full,
                                        const DistanceProbeAsset& half, bool layered);

// Which texel formats of the composite the plan weighs: float alone (the default), float and
// BC6H (a memory budget lets the plan pick the format), or BC6H alone (the user asked for it).
enum class PlanFormats { Float, FloatAndBc6h, Bc6h };

// `candidates` in the formats asked for: unchanged for Float, each also compressed right after
// it for FloatAndBc6h, each compressed instead for Bc6h.
void applyPlanFormats(std::vector<PlanCandidate>& candidates, PlanFormats formats);

// The probes candidates are scored on: the cook's resolution and half of it (the same probe
// when one resolution is weighed), and their compressed copies (compressComposite) when the
// plan weighs BC6H.
struct PlanAssets {
    const DistanceProbeAsset& full;
    const DistanceProbeAsset& half;
    const DistanceProbeAsset* fullBc6h = nullptr;
    const DistanceProbeAsset* halfBc6h = nullptr;
    // Throws std::logic_error for a compressed candidate without its compressed probe.
    const DistanceProbeAsset& of(const PlanCandidate& c) const;
};

// Scores every candidate on `rays` (the asset of its resolution and format), filling psnr,
// rmse, fetches, mib and cost. Per-ray errors are summed in ray order: the same rays give the
// same figures, bit for bit, whatever the threads. The cost model knows fetches and layers, not
// formats: a compressed candidate is predicted from its own fetches (its search steps on the
// stored distances), as if sampling BC6H cost what sampling float does.
void scoreCandidates(std::vector<PlanCandidate>& candidates, const PlanAssets& assets,
                     const std::vector<PlanRay>& rays, const CostModel& model);

// The choice: with a budget, the cheapest candidate meeting it; without, the cheapest within
// kNoBudgetSlackDb of the best PSNR. Cheapest: the lowest predicted cost at the precision
// printed (0.01 x envmap), then with a budget the fewest MiB and the higher PSNR, without one
// the higher PSNR and the fewest MiB, then list order. Sets
// `meets` on every candidate. No candidate meeting the budget: the best PSNR wins (cost
// breaks ties) and `warning` says so, naming max_error. A memory budget (`maxMib` > 0,
// --max-mib-per-probe) leaves out every candidate whose textures take more: they neither meet
// nor set the best PSNR; when none fits, the smallest measured one wins and `warning` says
// so. Returns the winner's index (-1 when nothing was measured); `reason` says why it won.
inline constexpr double kNoBudgetSlackDb = 0.5;
int choosePlanCandidate(std::vector<PlanCandidate>& candidates, const ErrorBudget& budget,
                        std::string& reason, std::string& warning, double maxMib = 0.0);

// The cost compared by the choice: predicted cost rounded to 0.01 x envmap.
double comparedCost(const PlanCandidate& c);

} // namespace specula
