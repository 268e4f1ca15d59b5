#pragma once
// Inference of one parameterized environment map (Hakura, Snyder, Lengyel 2001, §4 "EM
// Inference"; docs/design.md §5b): rendering is linear in the texels, so the map is the
// least-squares best match to the ray-traced radiance of the reflector's pixels as the lookup
// applies it. The rendering matrix A comes from PemLookupCpu::weights, the same code the shader
// runs; regularisation rows lambda * (t_a - t_b) over every pair of neighbouring texels (across
// cube edges too) fill the texels no sample sees from their neighbours and keep the rest
// from ringing. One solve per parameter sample; the samples come from Embree later.
#include "components/reflection_probe/pem/pem_lookup_cpu.h"

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

namespace specula {

// One reflector pixel at one parameter sample: probe-local reflector point x (inside the
// map's box), unit reflected direction l, and the radiance the ray tracer saw along it.
struct PemSample {
    glm::vec3 x{0.f};
    glm::vec3 l{0.f, 0.f, 1.f};
    glm::vec3 target{0.f};
    // Layered bakes (pem_layers.h) only: the radiance along the ray continued through the
    // reflector it leaves (the distant layer's target; other reflectors still reflect),
    // whether the ray meets that reflector again first, and whether it leaves from a triangle
    // on the reflector's hull (pem_hull.h), which never reads the local layer.
    glm::vec3 distant{0.f};
    bool selfHit = false;
    bool onHull = true;
    // The pixel's footprint as the shader differentiates it (PemFootprint: fine derivatives
    // of x and l along the window's x and y, per displayed pixel), which picks the MIP level
    // of multi-level maps. Zero: level 0.
    glm::vec3 dxdX{0.f}, dxdY{0.f}, dldX{0.f}, dldY{0.f};
    // The displayed pixel the ray is a sub-ray of (tracePemSamples: row-major in the camera
    // image, from its top row), which PemRows::Pixel and Centre average over; -1: a row of
    // its own. centre: the ray through the pixel's centre (every ray at supersample 1, the
    // middle sub-ray at an odd supersample), the one the rasteriser shades.
    int pixel = -1;
    bool centre = false;

    PemFootprint footprint() const { return {dxdX, dxdY, dldX, dldY}; }
};
using PemSamples = std::vector<PemSample>;

// What one data row of the rendering matrix is. SubRay: each traced ray, its own lookup
// weights against its own radiance. Pixel and Centre (Hakura §4: the target is the
// antialiased image): the sub-rays of one displayed pixel (PemSample::pixel) make one row
// whose target is the mean of their radiances (and coverage); its weights are, for Pixel,
// the mean of the sub-rays' lookup weights (a renderer that supersamples), for Centre, the
// lookup weights of the pixel's centre ray alone (PemSample::centre: what the rasteriser
// draws, one lookup a pixel at its footprint; a pixel whose centre misses the reflector is
// not drawn as reflector and has no row). A row is scaled by sqrt(count) so that it weighs
// in the least squares as the count rows it replaces (the smoothness and prior weights keep
// their meaning at any supersampling; a pixel only partly on the reflector counts for its
// covered part). A pixel's rays that miss every reflector are not traced, so the mean is
// over the sub-rays that land on one (every reflector reads the same maps). Supersample 1
// gives the SubRay rows exactly, whichever kind.
enum class PemRows { SubRay, Pixel, Centre };

struct PemInferOptions {
    int faceRes = 32;                    // 1 .. 1024
    glm::vec3 boxMin{-1.f}, boxMax{1.f}; // the map's box geometry, probe-local, min < max
    // Distance geometry (bakePemDistanceGeometry): the rows come from the distance-rectified
    // lookup and the inferred map carries this pointer. Null: box geometry.
    std::shared_ptr<const PemDistanceGeometry> distance;
    // lambda: weight of a neighbour-difference row against a sample row (whose weights sum
    // to 1). Small, so texels the samples pin follow the data (doubling it moves them by
    // 0.003 RMS in tests/pem), yet every unseen texel becomes the mean of its neighbours.
    // 0 leaves unseen texels at the starting guess.
    float regularisation = 0.02f;
    double tolerance = 1e-6;  // relative normal-equation residual |A^T r| / |A^T b|, per channel
    int maxIterations = 2000; // per channel
    // Start from this map's texels (e.g. the neighbouring parameter sample's); null: black.
    const std::vector<glm::vec3>* warmStart = nullptr;
    // Optional prior: one row priorWeight * (t - prior_t) per texel, so a texel no sample
    // sees falls back to the prior (e.g. the radiance captured at the centre,
    // bakePemDistanceGeometry's capturedRadiance) instead of only its neighbours' mean. Null
    // or priorWeight 0: no prior rows. Like lambda, weighed against sample rows summing to 1.
    const std::vector<glm::vec3>* prior = nullptr;
    float priorWeight = 0.f;
    // A local layer (pem_local_lookup.glsl.h): the rows come from the sphere lookup (box and
    // distance unused), and `alphaTargets` (one per sample, the ray's coverage) is solved
    // with the same matrix into map.alpha, clamped to [0, 1]. Its prior, when the RGB has one,
    // is 0: coverage nobody saw reads as the distant layer.
    std::optional<PemLocalSphere> local;
    const std::vector<float>* alphaTargets = nullptr;
    // MIP levels of the map, 1 .. PemMap::maxLevels(faceRes) (Hakura §4: all levels are
    // unknowns of one solve, each sample's row reading the levels its footprint picks).
    // Smoothness rows stay within a level; a level's prior is the prior box-filtered down
    // (pemBoxFilteredLevels); rows lambda * (parent - mean of its children) tie each texel to
    // the level above, so a level no footprint reaches becomes the filtered one. 1 for a local
    // layer. warmStart then holds every level.
    int mipLevels = 1;
    PemRows rows = PemRows::SubRay;
    // Active-set bounds (issue 12): the unconstrained solve drives texels far below zero
    // (-4 to -10 on the room) to buy residual elsewhere, and clamping them afterwards throws
    // that fit away. When set, after each solve every free texel below its bound (RGB < 0;
    // the local layer's alpha < 0 or > 1) is pinned there, removed as an unknown, and the
    // rest solved again warm-started from the previous solution, for at most
    // kPemBoundPasses re-solves per channel or until no new texel crosses. Pinned texels stay
    // pinned (no release step: deterministic and bounded); what still crosses after the last
    // pass is clamped as before.
    bool nonNegative = false;
    // Distance geometry only: rows for the lookups the display's rounding reaches
    // (pem_rounding_rows.h), x and l moved by this much (metres; radians) both ways along
    // each axis. 0: the rays' own lookups alone.
    float roundingReach = 0.f;
};

// Re-solves of the active-set bounds (PemInferOptions::nonNegative) per channel at most.
constexpr int kPemBoundPasses = 3;

struct PemInference {
    PemMap map; // clamped to [0, kMaxRadiance]
    // Over the data rows and RGB (pemRowsRms: a pixel row shows its sub-rays' mean lookup, a
    // centre row its centre ray's, against their mean target), of the clamped map.
    double residualRms = 0;
    int dataRows = 0;                // rows of the rendering matrix from the samples (PemRows)
    std::array<int, 3> iterations{}; // conjugate-gradient iterations per channel
    double solverError = 0;          // largest relative error estimate the solver reported
    double seconds = 0;              // building A, solving, measuring the residual
    int unseenTexels = 0;            // texels no sample reads with a weight above zero
    int roundingRows = 0;            // of dataRows: copies of rays moved by roundingReach
    // nonNegative: the texels pinned at a bound per channel (R, G, B, alpha), and the
    // re-solves run (all channels together).
    std::array<int, 4> pinnedTexels{};
    int boundPasses = 0;
};

// Throws Error naming the field: "samples" (none; a non-finite x, l or target; l not unit;
// Centre rows without a centre ray), "face_res", "box", "regularisation", "tolerance",
// "max_iterations", "warm_start", "prior", "prior_weight", "distance.*"
// (checkPemDistanceGeometry), "local" (a radius not > 0, or alpha targets without a sphere
// or not one per finite sample in [0, 1]), "mip_levels".
PemInference inferPemMap(const PemSamples& samples, const PemInferOptions& o);

// The data rows `rows` makes of `samples`: the samples' indices of each row, rows in order of
// their pixel (rows of pixel -1 first, one sample each, in sample order), each row's samples
// in sample order except that a Centre row starts with its centre ray (a pixel without one
// makes no Centre row). SubRay: one row per sample, in order.
std::vector<std::vector<int>> pemDataRows(const PemSamples& samples, PemRows rows);

// One data row's weights before inferPemMap's sqrt(count) scale, as (texel, weight) pairs by
// ascending texel, each texel once: lookup.weights at each sample's x, l and footprint,
// averaged over `members` (a row of pemDataRows), or for Centre those of members.front().
void pemRowWeights(const PemLookupCpu& lookup, const PemSamples& samples,
                   const std::vector<int>& members, PemRows rows,
                   std::vector<std::pair<int, double>>& out);

// RMS over RGB and `dataRows` (pemDataRows(samples, rows)) of what each row shows (`radiance`
// averaged over its samples, or for Centre its centre ray's) against its mean target.
double pemRowsRms(const PemSamples& samples, const std::vector<std::vector<int>>& dataRows,
                  PemRows rows, const std::function<glm::vec3(const PemSample&)>& radiance);

// Every unordered pair of texels that share a texel edge, within a face or across a cube
// edge (texel indices as PemMap), each pair once with first < second: 12 N^2 pairs, every
// texel in exactly four.
std::vector<std::pair<int, int>> pemNeighbourPairs(int faceRes);

} // namespace specula
