#pragma once
// The bench's error budget (issue 15): where each distance method's error on a scene comes
// from, measured by controlled experiments on the CPU twin (CpuDistanceProbe, the shader's
// own lookup compiled as C++) over the ground truth's reflector rays. Each experiment removes
// one source of error and the lookup is run again over the same rays:
//   search      (a) the method's way to the hit made exact (Experiment::exactSearch: the
//                   shared lookup's lookupExact in place of each layer's method, inside the
//                   shader's own layer loop, so the layered rules are not copied here)
//   resolution  (b) the probe baked with faces twice as large per side (4x texels)
//   silhouettes (c) radiance never filtered across a depth discontinuity
//                   (Experiment::sameSurfaceRadiance)
//   disocclusion (d) the rays whose truth hit the probe centre cannot see (centreView) given
//                   the truth's radiance: their share of the error
// A term is the baseline MSE less the experiment's. The residual is the least MSE any
// combination of the experiments leaves: what none of them explains (an experiment that
// hurts, as same-surface radiance does where the stored silhouette is off by a texel, is
// left out of it). `all` runs all four at once; the interaction (baseline - all - the terms)
// says how far the terms are from additive. `oracle` hands the lookup the truth's hit
// (the radiance the centre holds in the direction of the truth's hit point): the floor of any
// search over this probe, what the centre cannot see plus resolution.
#include "components/reflection_probe/distance/distance_probe.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/image/image.h"
#include "engine/math/camera.h"

#include <glm/glm.hpp>

#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace specula {

class ReflectionScene;

// One reflector pixel's reflected ray, probe-local, and what the truth saw along it.
struct BudgetRay {
    glm::vec3 x{0.f};     // reflector point, probe-local
    glm::vec3 l{0.f};     // unit reflected direction
    glm::vec3 truth{0.f}; // environment-only ground truth radiance (the bench's reference)
    glm::vec3 hit{0.f};   // the truth's hit point, probe-local (when hasHit)
    bool hasHit = false;  // false: the ray left for the sky
};

// The rays of the reflector pixels of `mask` (channel 0 > 0.5) seen from `camera`, traced
// by Embree as the ground truth traces them (mirror about the shading normal turned to the
// viewer); truth: the environment-only image the bench compares against, at that pixel.
// `centre`: the probe's world position.
std::vector<BudgetRay> traceBudgetRays(ReflectionScene& scene, const CameraView& camera,
                                       const Image& mask, const Image& envTruth, glm::vec3 centre);

constexpr double kNoFigure = std::numeric_limits<double>::quiet_NaN();

// MSE over RGB (the bench's RMSE squared) of each lookup over the rays.
struct MethodErrorBudget {
    std::string scene, method, params;
    std::size_t rays = 0;
    double base = 0;          // the twin as the shader runs
    double exact = 0;         // (a) exact search
    double res2x = kNoFigure; // (b) faces 2x per side; NaN when not baked
    double sameSurface = 0;   // (c) no radiance filtering across silhouettes
    double seen = 0;          // (d) rays the centre cannot see take the truth
    double all = 0;           // every experiment at once (res2x when baked)
    // The least MSE any combination of the experiments leaves (what none of them explains)
    // and that combination ("search+resolution+disocclusion"; "none": the baseline itself).
    double residual = 0;
    std::string residualSet;
    double oracle = 0;         // the truth's hit handed to the lookup
    double hiddenShare = 0;    // share of rays whose truth hit the centre cannot see
    double gpuMse = kNoFigure; // the GPU row's RMSE squared, for the twin's gap
    // (e) the baseline with every layer, the composite included, stored as RGBA16F: what
    // half floats cost against float32 (NaN where the layers do not fit half floats).
    double halfFloat = kNoFigure;
    // (f) the baseline with every layer compressed as `--compress bc6h` stores it: radiance
    // in BC6H, distance in half floats (distance_compression.h).
    double bc6h = kNoFigure;
    // The probe's layers on the GPU (cubes without mips) as RGBA32F, RGBA16F and BC6H + R16F.
    std::size_t bytesFloat = 0, bytesHalf = 0, bytesBc6h = 0;
    std::string res2xNote; // why res2x is missing, when it is

    double termSearch() const { return base - exact; }
    double termResolution() const { return base - res2x; } // NaN without res2x
    double termSilhouettes() const { return base - sameSurface; }
    double termDisocclusion() const { return base - seen; }
    // baseline - all - the terms: 0 when the terms add up; NaN terms count as 0.
    double interaction() const;
    // The largest of the four terms: "search", "resolution", "silhouettes", "disocclusion";
    // "none" when no term is positive.
    std::string dominant() const;
};

// The probe's baseline lookups and experiments over `rays`: `asset` with `settings` (the
// bench row's), `asset2x` the same scene baked with faces twice as large (null: res2x is
// left NaN and `all` runs at the asset's own size). Throws Error naming the asset when the
// method needs data it lacks (makeLookupConfig).
// The probe as the storage experiments hold it ((e) RGBA16F where every layer fits, (f) BC6H
// + half distance): made once per probe, as BC6H encoding takes seconds, and shared by its
// methods' budgets.
struct StoredProbeVariants {
    std::optional<DistanceProbeAsset> half;
    DistanceProbeAsset bc6h;
};
StoredProbeVariants storedProbeVariants(const DistanceProbeAsset& asset);

MethodErrorBudget
measureErrorBudget(const std::vector<BudgetRay>& rays, const DistanceProbe& settings,
                   const DistanceProbeAsset& asset, const DistanceProbeAsset* asset2x,
                   const StoredProbeVariants* stored = nullptr); // null: made here

// error_budget.png: one panel per scene, one stacked bar per method, its height the
// baseline MSE taken as 1: the four terms (negative ones left out), then the residual (the
// least any combination of the experiments leaves); a white tick marks the baseline, so a stack
// above it shows terms that overlap and one below it terms that only act together. The baseline
// PSNR is written above each bar. Drawn with PlotCanvas, like accuracy_vs_time.png.
Image errorBudgetPlot(const std::vector<MethodErrorBudget>& budgets,
                      const std::vector<std::string>& scenes, int panelWidth = 640,
                      int panelHeight = 480);

// The budget's bench.csv columns: the header (leading comma) and one row's values (empty
// for a row without a budget), appended after the bench's own columns.
std::string errorBudgetCsvHeader();
std::string errorBudgetCsvValues(const MethodErrorBudget* b);

// bench.md's budget table of one scene (empty when it has no budget).
std::string errorBudgetMarkdown(const std::vector<MethodErrorBudget>& budgets,
                                const std::string& scene);

// 10 log10(1 / mse): the bench's PSNR (peak 1) of an MSE; inf for 0.
double psnrOfMse(double mse);

} // namespace specula
