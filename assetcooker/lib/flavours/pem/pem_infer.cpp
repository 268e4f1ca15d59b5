#include "assetcooker/lib/flavours/pem/pem_infer.h"

#include "assetcooker/lib/flavours/pem/pem_rounding_rows.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "components/reflection_probe/pem/pem_map_levels.h"
#include "engine/core/error.h"
#include "engine/core/flush_denormals.h"
#include "engine/core/glsl_host.h"
#include "engine/math/cube_face.h"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace specula {

namespace {

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void validate(const PemSamples& samples, const PemInferOptions& o) {
    if (samples.empty()) throw Error("", "samples", "expected at least one sample, got none");
    for (std::size_t s = 0; s < samples.size(); ++s) {
        const PemSample& p = samples[s];
        const std::string which = "sample " + std::to_string(s);
        if (!finite(p.x) || !finite(p.l))
            throw Error("", "samples", which + ": expected a finite ray (x, l)");
        // The box lookup measures distance along l: a non-unit l would scale the hit.
        if (!(std::abs(glm::length(p.l) - 1.f) < 1e-3f))
            throw Error("", "samples", which + ": expected a unit direction l");
        if (!finite(p.target)) throw Error("", "samples", which + ": expected a finite target");
    }
    if (o.faceRes < 1 || o.faceRes > 1024)
        throw Error("", "face_res", "expected 1 to 1024, got " + std::to_string(o.faceRes));
    if (!finite(o.boxMin) || !finite(o.boxMax) || !(o.boxMin.x < o.boxMax.x) ||
        !(o.boxMin.y < o.boxMax.y) || !(o.boxMin.z < o.boxMax.z))
        throw Error("", "box", "expected finite bounds with min < max on every axis");
    if (!(o.regularisation >= 0.f) || !std::isfinite(o.regularisation))
        throw Error("", "regularisation", "expected a finite lambda >= 0");
    if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
        throw Error("", "tolerance", "expected a finite tolerance > 0");
    if (o.maxIterations < 1) throw Error("", "max_iterations", "expected at least 1");
    if (o.mipLevels < 1 || o.mipLevels > PemMap::maxLevels(o.faceRes) ||
        (o.local && o.mipLevels != 1))
        throw Error("", "mip_levels",
                    "expected 1 to " + std::to_string(PemMap::maxLevels(o.faceRes)) +
                        " levels (1 for a local layer), got " + std::to_string(o.mipLevels));
    if (o.warmStart) {
        bool ok = o.warmStart->size() == std::size_t(PemMap::texelCount(o.faceRes, o.mipLevels));
        for (std::size_t t = 0; ok && t < o.warmStart->size(); ++t)
            ok = finite((*o.warmStart)[t]);
        if (!ok) throw Error("", "warm_start", "expected every level's texels, all finite");
    }
    if (o.prior) {
        bool ok = o.prior->size() == std::size_t(PemMap::texelCount(o.faceRes));
        for (std::size_t t = 0; ok && t < o.prior->size(); ++t)
            ok = finite((*o.prior)[t]);
        if (!ok) throw Error("", "prior", "expected 6 * face_res^2 finite texels");
    }
    if (!(o.priorWeight >= 0.f) || !std::isfinite(o.priorWeight))
        throw Error("", "prior_weight", "expected a finite weight >= 0");
    if (o.distance) checkPemDistanceGeometry(*o.distance, "", "");
    if (o.local &&
        (!(o.local->radius > 0.f) || !std::isfinite(o.local->radius) || !finite(o.local->centre)))
        throw Error("", "local", "expected a finite sphere of radius > 0");
    if (o.alphaTargets) {
        bool ok = o.local && o.alphaTargets->size() == samples.size();
        for (std::size_t s = 0; ok && s < samples.size(); ++s)
            ok = (*o.alphaTargets)[s] >= 0.f && (*o.alphaTargets)[s] <= 1.f;
        if (!ok)
            throw Error("", "local",
                        "expected one coverage in [0, 1] per sample, with a local sphere");
    }
}

// Clamp to what a cooked probe may hold; NaN (never expected from finite input) reads 0.
float toRange(double v) {
    return v > 0.0 ? float(std::min(v, double(kMaxRadiance))) : 0.f;
}

// Rows lambda * (parent - mean of its children) from `row` on, one per texel of levels 1 ..
// levels-1, the children as pemBoxFilteredLevels averages them. Returns the next row.
int appendLevelRows(int faceRes, int levels, double lambda, int row,
                    std::vector<Eigen::Triplet<double>>& entries) {
    forEachPemLevelParent(faceRes, levels, [&](int parent, const int* children, int count) {
        entries.emplace_back(row, parent, lambda);
        for (int c = 0; c < count; ++c)
            entries.emplace_back(row, children[c], -lambda / double(count));
        ++row;
    });
    return row;
}

using SparseMatrix = Eigen::SparseMatrix<double>;
using Solver = Eigen::LeastSquaresConjugateGradient<SparseMatrix>;

struct ChannelSolve {
    Eigen::VectorXd x;
    int iterations = 0;
    double error = 0;
    int pinned = 0; // texels pinned at a bound
    int passes = 0; // re-solves run
};

// The least-squares solution of A x = b from `guess` (`full`: the solver computed on A); with
// `bounded`, the active-set passes of PemInferOptions::nonNegative keeping x in [0, upper].
// A pinned texel's column times its bound moves to the right-hand side, its column leaves
// the matrix (A S, S selecting the free columns), and the rest are solved again from where
// the previous pass left them.
ChannelSolve solveChannel(const SparseMatrix& A, Solver& full, const Eigen::VectorXd& b,
                          const Eigen::VectorXd& guess, bool bounded, double upper,
                          const PemInferOptions& o) {
    ChannelSolve out;
    out.x = full.solveWithGuess(b, guess);
    out.iterations = int(full.iterations());
    out.error = double(full.error());
    if (!bounded) return out;
    const Eigen::Index n = A.cols();
    std::vector<signed char> pinned(std::size_t(n), 0); // 0 free, -1 at 0, +1 at upper
    for (int pass = 0; pass < kPemBoundPasses; ++pass) {
        bool crossed = false;
        for (Eigen::Index t = 0; t < n; ++t) {
            signed char& p = pinned[std::size_t(t)];
            if (p != 0 || !(out.x[t] < 0.0 || out.x[t] > upper)) continue;
            p = out.x[t] < 0.0 ? -1 : 1;
            crossed = true;
            ++out.pinned;
        }
        if (!crossed) break;
        std::vector<Eigen::Triplet<double>> select;
        Eigen::VectorXd fixed = Eigen::VectorXd::Zero(n), start;
        for (Eigen::Index t = 0; t < n; ++t) {
            const signed char p = pinned[std::size_t(t)];
            if (p == 0)
                select.emplace_back(int(t), int(select.size()), 1.0);
            else if (p > 0)
                fixed[t] = upper;
        }
        if (select.empty()) {
            out.x = fixed;
            break;
        }
        SparseMatrix S(n, Eigen::Index(select.size()));
        S.setFromTriplets(select.begin(), select.end());
        const SparseMatrix free = A * S;
        start.resize(S.cols());
        for (std::size_t i = 0; i < select.size(); ++i)
            start[Eigen::Index(i)] = out.x[select[i].row()];
        Solver solver;
        solver.setTolerance(o.tolerance);
        solver.setMaxIterations(o.maxIterations);
        solver.compute(free);
        const Eigen::VectorXd y = solver.solveWithGuess(b - A * fixed, start);
        out.x = fixed;
        for (std::size_t i = 0; i < select.size(); ++i)
            out.x[select[i].row()] = y[Eigen::Index(i)];
        out.iterations += int(solver.iterations());
        out.error = std::max(out.error, double(solver.error()));
        ++out.passes;
    }
    return out;
}

} // namespace

double pemRowsRms(const PemSamples& samples, const std::vector<std::vector<int>>& dataRows,
                  PemRows rows, const std::function<glm::vec3(const PemSample&)>& radiance) {
    double sum = 0;
    for (const std::vector<int>& members : dataRows) {
        glm::dvec3 shown(0.0), target(0.0);
        const std::size_t used = rows == PemRows::Centre ? 1 : members.size();
        for (std::size_t m = 0; m < members.size(); ++m) {
            const PemSample& p = samples[std::size_t(members[m])];
            if (m < used) shown += glm::dvec3(radiance(p));
            target += glm::dvec3(p.target);
        }
        const glm::dvec3 d = shown / double(used) - target / double(members.size());
        sum += glm::dot(d, d);
    }
    return dataRows.empty() ? 0.0 : std::sqrt(sum / (3.0 * double(dataRows.size())));
}

std::vector<std::vector<int>> pemDataRows(const PemSamples& samples, PemRows rows) {
    std::vector<int> order(samples.size());
    std::iota(order.begin(), order.end(), 0);
    if (rows != PemRows::SubRay)
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
            return samples[std::size_t(a)].pixel < samples[std::size_t(b)].pixel;
        });
    std::vector<std::vector<int>> out;
    int previous = -1;
    for (const int s : order) {
        const int pixel = samples[std::size_t(s)].pixel;
        if (rows == PemRows::SubRay || pixel < 0 || out.empty() || pixel != previous)
            out.emplace_back();
        out.back().push_back(s);
        previous = pixel;
    }
    if (rows != PemRows::Centre) return out;
    // The centre ray first; a pixel without one is not drawn as reflector. A sample of
    // pixel -1 is its own centre.
    std::vector<std::vector<int>> kept;
    kept.reserve(out.size());
    for (std::vector<int>& members : out) {
        const auto c = std::find_if(members.begin(), members.end(), [&](int s) {
            return samples[std::size_t(s)].centre || samples[std::size_t(s)].pixel < 0;
        });
        if (c == members.end()) continue;
        std::rotate(members.begin(), c, c + 1);
        kept.push_back(std::move(members));
    }
    return kept;
}

void pemRowWeights(const PemLookupCpu& lookup, const PemSamples& samples,
                   const std::vector<int>& members, PemRows rows,
                   std::vector<std::pair<int, double>>& out) {
    out.clear();
    PemWeights w;
    const std::size_t used = rows == PemRows::Centre ? 1 : members.size();
    for (std::size_t m = 0; m < used; ++m) {
        const int s = members[m];
        const PemSample& p = samples[std::size_t(s)];
        lookup.weights(p.x, p.l, w, p.footprint());
        for (const auto& [t, weight] : w)
            out.emplace_back(t, double(weight));
    }
    // By texel, sub-rays in sample order within one (a fixed summation order).
    std::stable_sort(out.begin(), out.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t kept = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        if (kept > 0 && out[kept - 1].first == out[i].first)
            out[kept - 1].second += out[i].second;
        else
            out[kept++] = out[i];
    }
    out.resize(kept);
    for (auto& [t, weight] : out)
        weight /= double(used);
}

std::vector<std::pair<int, int>> pemNeighbourPairs(int faceRes) {
    const int n = faceRes;
    auto index = [n](int face, int i, int j) { return (face * n + j) * n + i; };
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(std::size_t(12 * n * n + 12 * n));
    const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const int a = index(face, i, j);
                for (const auto& st : steps) {
                    const int i2 = i + st[0], j2 = j + st[1];
                    if (i2 >= 0 && i2 < n && j2 >= 0 && j2 < n) {
                        if (st[0] + st[1] > 0) pairs.emplace_back(a, index(face, i2, j2));
                        continue;
                    }
                    // One texel step past the edge, on the face's plane extended, folds onto
                    // the adjacent face's edge row at the same texel along the edge: that
                    // point's coordinates are those of a texel centre scaled by N / (N + 1),
                    // which stays inside the texel, so the floor below is exact.
                    const glm::vec2 uv((float(i2) + 0.5f) / float(n),
                                       (float(j2) + 0.5f) / float(n));
                    const glm::vec3 f = glsl::cubeFaceUv(glsl::cubeFaceDirection(face, uv));
                    const int b = index(int(f.z), std::min(int(f.x * float(n)), n - 1),
                                        std::min(int(f.y * float(n)), n - 1));
                    pairs.emplace_back(std::min(a, b), std::max(a, b));
                }
            }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}

PemInference inferPemMap(const PemSamples& samples, const PemInferOptions& o) {
    validate(samples, o);
    const auto start = std::chrono::steady_clock::now();

    PemInference r;
    PemMap& map = r.map;
    map.faceRes = o.faceRes;
    map.boxMin = o.boxMin;
    map.boxMax = o.boxMax;
    map.distance = o.local ? nullptr : o.distance;
    map.local = o.local;
    map.levels = o.mipLevels;
    const int texels = PemMap::texelCount(o.faceRes, o.mipLevels);
    const PemLookupCpu lookup(map); // weights need the geometry only

    // Data rows first (pemDataRows): a row's mean weights (pemRowWeights) times sqrt(count),
    // weighed as the count rows it stands for; then one row per neighbour pair.
    using Triplet = Eigen::Triplet<double>;
    std::vector<Triplet> entries;
    std::vector<char> seen(std::size_t(texels), 0);
    std::vector<std::pair<int, double>> w;
    // The rays, and where the display's rounding can take their lookups (each a row of its
    // own, after the rays: the indices of `samples` stay those of its rows).
    PemSamples withCopies;
    const bool copies = o.roundingReach > 0.f && o.distance && !o.local;
    if (copies) {
        withCopies = samples;
        const PemSamples extra = pemRoundingCopies(lookup, samples, o.roundingReach);
        withCopies.insert(withCopies.end(), extra.begin(), extra.end());
        r.roundingRows = int(extra.size());
    }
    const PemSamples& rowSamples = copies ? withCopies : samples;
    const std::vector<std::vector<int>> dataRows = pemDataRows(rowSamples, o.rows);
    const int sampleRows = int(dataRows.size());
    if (sampleRows == 0)
        throw Error("", "samples", "expected a pixel's centre ray among the samples (centre rows)");
    // A row's right-hand side is sqrt(count) * mean target = (sum of targets) * sumScale.
    std::vector<double> sumScale(dataRows.size());
    for (int row = 0; row < sampleRows; ++row) {
        const std::vector<int>& members = dataRows[std::size_t(row)];
        sumScale[std::size_t(row)] = 1.0 / std::sqrt(double(members.size()));
        pemRowWeights(lookup, rowSamples, members, o.rows, w);
        const double scale = std::sqrt(double(members.size()));
        for (const auto& [t, weight] : w) {
            entries.emplace_back(row, t, weight * scale);
            seen[std::size_t(t)] = 1;
        }
    }
    r.dataRows = sampleRows;
    r.unseenTexels = int(std::count(seen.begin(), seen.end(), char(0)));
    int rows = sampleRows;
    if (o.regularisation > 0.f) {
        const double lambda = o.regularisation;
        for (int level = 0; level < o.mipLevels; ++level) {
            const int offset = PemMap::levelOffset(o.faceRes, level);
            for (const auto& [a, b] : pemNeighbourPairs(PemMap::levelRes(o.faceRes, level))) {
                entries.emplace_back(rows, offset + a, lambda);
                entries.emplace_back(rows, offset + b, -lambda);
                ++rows;
            }
        }
        rows = appendLevelRows(o.faceRes, o.mipLevels, lambda, rows, entries);
    }
    // Prior rows: w (t - prior_t), the prior's part going to the right-hand side; every
    // level's prior is the level-0 prior box-filtered down.
    const bool usePrior = o.prior && o.priorWeight > 0.f;
    const int priorRow = rows;
    std::vector<glm::vec3> prior;
    if (usePrior) {
        prior = pemBoxFilteredLevels(*o.prior, o.faceRes, o.mipLevels);
        for (int t = 0; t < texels; ++t)
            entries.emplace_back(rows++, t, double(o.priorWeight));
    }
    Eigen::SparseMatrix<double> A(rows, texels);
    A.setFromTriplets(entries.begin(), entries.end());

    map.texels.assign(std::size_t(texels), glm::vec3(0.f));
    // Channel 3 is the local layer's coverage: the same rows, its prior 0.
    const int channels = o.alphaTargets ? 4 : 3;
    // A local map without coverage targets (a refit of its RGB) still holds one alpha per
    // texel, so the residual below can look it up; the caller keeps its own.
    if (o.alphaTargets || o.local) map.alpha.assign(std::size_t(texels), 0.f);
    // The channels share the matrix and nothing else: solved side by side, each with its own
    // solver (an Eigen solver keeps its last solve's figures, so one cannot serve two threads
    // at once), with denormals flushed whichever thread runs it (flush_denormals.h): the same
    // bits every run. Room, 256², 9 levels, two layers: 11.6 -> 8.8 s a sample on 2 cores.
    std::vector<ChannelSolve> solved(static_cast<std::size_t>(channels));
    tbb::parallel_for(0, channels, [&](int c) {
        const ScopedFlushDenormals sameBitsOnAnyThread;
        Eigen::VectorXd b = Eigen::VectorXd::Zero(rows), guess = Eigen::VectorXd::Zero(texels);
        for (int row = 0; row < sampleRows; ++row) {
            double sum = 0;
            for (const int s : dataRows[std::size_t(row)])
                sum += c < 3 ? double(rowSamples[std::size_t(s)].target[c])
                             : double((*o.alphaTargets)[std::size_t(s)]);
            b[row] = sum * sumScale[std::size_t(row)];
        }
        if (usePrior)
            for (int t = 0; t < texels; ++t)
                b[priorRow + t] = c < 3 ? double(o.priorWeight) * prior[std::size_t(t)][c] : 0.0;
        if (o.warmStart && c < 3)
            for (int t = 0; t < texels; ++t)
                guess[t] = (*o.warmStart)[std::size_t(t)][c];
        Solver solver;
        solver.setTolerance(o.tolerance);
        solver.setMaxIterations(o.maxIterations);
        solver.compute(A);
        // Radiance has no upper bound before the clamp; coverage is at most 1.
        solved[std::size_t(c)] =
            solveChannel(A, solver, b, guess, o.nonNegative,
                         c < 3 ? std::numeric_limits<double>::infinity() : 1.0, o);
    });
    for (int c = 0; c < channels; ++c) {
        const Eigen::VectorXd& x = solved[std::size_t(c)].x;
        if (c < 3) r.iterations[std::size_t(c)] = solved[std::size_t(c)].iterations;
        r.solverError = std::max(r.solverError, solved[std::size_t(c)].error);
        r.pinnedTexels[std::size_t(c)] = solved[std::size_t(c)].pinned;
        r.boundPasses += solved[std::size_t(c)].passes;
        for (int t = 0; t < texels; ++t) {
            if (c < 3)
                map.texels[std::size_t(t)][c] = toRange(x[t]);
            else
                map.alpha[std::size_t(t)] = x[t] > 0.0 ? float(std::min(x[t], 1.0)) : 0.f;
        }
    }

    // The residual of what will be displayed: the clamped map through the lookup itself.
    // A row's residual as it was fitted (pemRowsRms).
    r.residualRms =
        pemRowsRms(samples, copies ? pemDataRows(samples, o.rows) : dataRows, o.rows,
                   [&](const PemSample& p) { return lookup.radiance(p.x, p.l, p.footprint()); });
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
}

} // namespace specula
