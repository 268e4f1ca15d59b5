#include "assetcooker/lib/plan/plan_candidates.h"

#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/distance_probe_cpu.h"
#include "components/reflection_probe/distance/distance_textures.h"
#include "engine/core/error.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <tuple>

namespace specula {

namespace {

constexpr float kTolerances[] = {0.1f, 0.03f, 0.01f};
constexpr const char* kSearches[] = {"bisection", "secant", "march"};

// Whether some object layer of `a` searches (its accuracy depends on d_e).
bool layersSearch(const DistanceProbeAsset& a) {
    for (std::size_t i = 1; i < a.layers.size(); ++i)
        if (const DistanceMethodInfo* row = findDistanceMethod(a.layers[i].method))
            if (row->usesTolerance) return true;
    return false;
}

DistanceProbe settingsOf(const PlanCandidate& c) {
    DistanceProbe p;
    p.method =
        c.method == "layered" ? DistanceMethod::Planned : findDistanceMethod(c.method)->method;
    // Methods that do not search ignore d_e; the probe's default stands in.
    if (c.tolerance > 0.f) p.errorTolerance = c.tolerance;
    return p;
}

std::string fixed(double v, int digits) {
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

// Why the winner's format: what its twin in the other format (same method, d_e, resolution
// and layers) reaches or takes; empty when the plan weighed one format.
template <class Fits>
std::string formatReason(const std::vector<PlanCandidate>& cs, const PlanCandidate& w,
                         const Fits& fits) {
    for (const PlanCandidate& c : cs) {
        if (c.compressed == w.compressed || c.method != w.method || c.tolerance != w.tolerance ||
            c.faceRes != w.faceRes || c.objectLayers != w.objectLayers || !c.measured())
            continue;
        const std::string mine = w.compressed ? "BC6H" : "float",
                          other = c.compressed ? "BC6H" : "float";
        return "; stored " + mine + " (" + fixed(w.mib, 1) + " MiB, " + fixed(w.psnr, 2) +
               " dB): " + other + " " +
               (fits(c) ? "reaches " + fixed(c.psnr, 2) + " dB in " + fixed(c.mib, 1) + " MiB"
                        : "takes " + fixed(c.mib, 1) + " MiB");
    }
    return "";
}

} // namespace

std::string PlanCandidate::label() const {
    std::string s = method;
    if (tolerance > 0.f) {
        char b[32];
        std::snprintf(b, sizeof b, " d_e=%g", double(tolerance));
        s += b;
    }
    return s + " " + std::to_string(faceRes) + "^2" + (compressed ? " bc6h" : "");
}

void applyPlanFormats(std::vector<PlanCandidate>& candidates, PlanFormats formats) {
    if (formats == PlanFormats::Float) return;
    std::vector<PlanCandidate> out;
    for (const PlanCandidate& c : candidates) {
        if (formats == PlanFormats::FloatAndBc6h) out.push_back(c);
        out.push_back(c);
        out.back().compressed = true;
    }
    candidates = std::move(out);
}

const DistanceProbeAsset& PlanAssets::of(const PlanCandidate& c) const {
    const bool fullRes = c.faceRes == full.faceRes;
    if (!c.compressed) return fullRes ? full : half;
    const DistanceProbeAsset* a = fullRes ? fullBc6h : halfBc6h;
    if (!a) throw std::logic_error("PlanAssets: " + c.label() + " without its compressed probe");
    return *a;
}

std::vector<PlanCandidate> candidateSet(const DistanceProbeAsset& full,
                                        const DistanceProbeAsset& half, bool layered) {
    std::vector<PlanCandidate> out;
    for (const DistanceProbeAsset* a : {&full, &half}) {
        auto add = [&](const std::string& method, float tolerance, int layers) {
            PlanCandidate c;
            c.method = method;
            c.tolerance = tolerance;
            c.faceRes = a->faceRes;
            c.objectLayers = layers;
            out.push_back(c);
        };
        for (const char* m : {"envmap", "boxproj", "avgdist"})
            add(m, 0.f, 0);
        for (const char* m : kSearches)
            for (float t : kTolerances)
                add(m, t, 0);
        if (layered && a->objectLayerCount() > 0) {
            if (layersSearch(*a))
                for (float t : kTolerances)
                    add("layered", t, a->objectLayerCount());
            else
                add("layered", 0.f, a->objectLayerCount());
        }
        if (half.faceRes == full.faceRes) break; // one resolution only
    }
    return out;
}

void scoreCandidates(std::vector<PlanCandidate>& candidates, const PlanAssets& assets,
                     const std::vector<PlanRay>& rays, const CostModel& model) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> sq(rays.size());
    std::vector<int> fetches(rays.size());
    for (PlanCandidate& c : candidates) {
        const DistanceProbeAsset& a = assets.of(c);
        const std::size_t composite =
            c.compressed ? compositeBytes(a) : cubeArrayBytes(c.faceRes, 1);
        c.mib = double(composite +
                       (c.objectLayers > 0 ? cubeArrayBytes(c.faceRes, c.objectLayers) : 0) +
                       (a.sky.empty() ? 0 : skyTextureBytes(a.sky))) /
                (1024.0 * 1024.0);
        std::unique_ptr<CpuDistanceProbe> twin;
        try {
            twin = std::make_unique<CpuDistanceProbe>(a, makeLookupConfig(settingsOf(c), a));
        } catch (const Error& e) {
            c.psnr = c.rmse = c.fetches = c.cost = nan;
            c.note = e.message();
            continue;
        }
        tbb::parallel_for(std::size_t(0), rays.size(), [&](std::size_t i) {
            int n = 0;
            const glm::vec3 got = twin->radiance(rays[i].origin - a.centre, rays[i].dir, n);
            const glm::vec3 d = got - rays[i].truth;
            sq[i] = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
            fetches[i] = n;
        });
        double sum = 0.0;
        long long f = 0;
        for (std::size_t i = 0; i < rays.size(); ++i)
            sum += sq[i], f += fetches[i];
        const double count = double(std::max<std::size_t>(rays.size(), 1));
        c.rmse = std::sqrt(sum / (3.0 * count));
        c.psnr = c.rmse > 0.0 ? 20.0 * std::log10(1.0 / c.rmse)
                              : std::numeric_limits<double>::infinity();
        c.fetches = double(f) / count;
        c.cost = model.predict(c.fetches, c.objectLayers);
    }
}

double comparedCost(const PlanCandidate& c) {
    return std::round(c.cost * 100.0) / 100.0;
}

int choosePlanCandidate(std::vector<PlanCandidate>& cs, const ErrorBudget& budget,
                        std::string& reason, std::string& warning, double maxMib) {
    reason.clear();
    warning.clear();
    const auto fits = [maxMib](const PlanCandidate& c) { return maxMib <= 0.0 || c.mib <= maxMib; };
    const std::string memoryText =
        maxMib > 0.0 ? " in at most " + fixed(maxMib, 1) + " MiB per probe" : "";
    int best = -1;
    for (int i = 0; i < int(cs.size()); ++i) {
        const PlanCandidate& c = cs[std::size_t(i)];
        if (!c.measured() || !fits(c)) continue;
        if (best < 0 || c.psnr > cs[std::size_t(best)].psnr ||
            (c.psnr == cs[std::size_t(best)].psnr &&
             comparedCost(c) < comparedCost(cs[std::size_t(best)])))
            best = i;
    }
    if (best < 0) {
        // Nothing measured fits the memory budget: the smallest measured, said so.
        int smallest = -1;
        for (int i = 0; i < int(cs.size()); ++i) {
            const PlanCandidate& c = cs[std::size_t(i)];
            cs[std::size_t(i)].meets = false;
            if (c.measured() &&
                (smallest < 0 ||
                 std::make_pair(c.mib, -c.psnr) < std::make_pair(cs[std::size_t(smallest)].mib,
                                                                 -cs[std::size_t(smallest)].psnr)))
                smallest = i;
        }
        if (smallest < 0) return -1;
        const PlanCandidate& s = cs[std::size_t(smallest)];
        warning = "no candidate fits --max-mib-per-probe " + fixed(maxMib, 1) +
                  " MiB: the smallest, " + s.label() + " at " + fixed(s.mib, 1) + " MiB, is used";
        reason = "fewest MiB; nothing fits" + memoryText;
        return smallest;
    }
    const double bestPsnr = cs[std::size_t(best)].psnr;
    for (PlanCandidate& c : cs)
        c.meets = c.measured() && fits(c) &&
                  (budget.kind == ErrorBudget::Kind::None ? c.psnr >= bestPsnr - kNoBudgetSlackDb
                                                          : budget.met(c.psnr, c.rmse));
    // At equal predicted time a budget lets memory decide (anything meeting it is good
    // enough); without one the slack is for time only, and the better picture wins before
    // the smaller one: the slack is narrower than the sampling noise of a gap between two
    // candidates (measured up to 1.3 dB), so spending it on memory gave up resolution the
    // bench then showed (truck_room at 1024x768: 128^2 layers 1.16 dB under 256^2).
    const bool budgetGiven = budget.kind != ErrorBudget::Kind::None;
    auto key = [&](const PlanCandidate& c) {
        return budgetGiven ? std::make_tuple(comparedCost(c), c.mib, -c.psnr)
                           : std::make_tuple(comparedCost(c), -c.psnr, c.mib);
    };
    int win = -1, meeting = 0;
    for (int i = 0; i < int(cs.size()); ++i) {
        if (!cs[std::size_t(i)].meets) continue;
        ++meeting;
        if (win < 0 || key(cs[std::size_t(i)]) < key(cs[std::size_t(win)])) win = i;
    }
    const std::string budgetText =
        budget.kind == ErrorBudget::Kind::None
            ? "within " + fixed(kNoBudgetSlackDb, 1) + " dB of the best measured (" +
                  fixed(bestPsnr, 2) + " dB, no max_error given)" + memoryText
            : "max_error " + budget.text() + " (" + budget.source + ")" + memoryText;
    if (win < 0) {
        const PlanCandidate& b = cs[std::size_t(best)];
        warning = "no candidate meets max_error " + budget.text() + " (" + budget.source +
                  "): the best measured, " + b.label() + " at " + fixed(b.psnr, 2) + " dB / rmse " +
                  fixed(b.rmse, 4) + ", is used";
        reason = "best measured PSNR; nothing meets " + budgetText;
        return best;
    }
    const PlanCandidate& w = cs[std::size_t(win)];
    reason = "cheapest (" + fixed(w.cost, 2) + "x envmap predicted, " +
             (budgetGiven ? fixed(w.mib, 1) + " MiB" : fixed(w.psnr, 2) + " dB") + ") of the " +
             std::to_string(meeting) + " candidates meeting " + budgetText;
    // The nearest cheaper candidate that misses: what the budget ruled out.
    int cheaper = -1;
    for (int i = 0; i < int(cs.size()); ++i) {
        const PlanCandidate& c = cs[std::size_t(i)];
        if (!c.measured() || c.meets || comparedCost(c) >= comparedCost(w)) continue;
        if (cheaper < 0 || comparedCost(c) > comparedCost(cs[std::size_t(cheaper)])) cheaper = i;
    }
    if (cheaper >= 0) {
        const PlanCandidate& c = cs[std::size_t(cheaper)];
        reason += "; the next cheaper, " + c.label() + " (" + fixed(c.cost, 2) + "x), " +
                  (fits(c) ? "reaches " + fixed(c.psnr, 2) + " dB / rmse " + fixed(c.rmse, 4)
                           : "takes " + fixed(c.mib, 1) + " MiB");
    }
    reason += formatReason(cs, w, fits);
    return win;
}

} // namespace specula
