#pragma once
// The two-layer maps of Hakura, Snyder, Lengyel 2001 (§4; docs/design.md §5b) on the cooker's side.
// A reflector ray that meets its own reflector again (a concave bowl seeing itself) reads a
// different bounce from what its neighbours read through the same texel of one map, so one
// map cannot hold both. The distant layer (the map of pem_infer.h) is fitted to the ray
// continued THROUGH its own reflector; the local layer (a sphere fitted to the reflector,
// pem_local_lookup.glsl.h) to alpha * full radiance with alpha = 1 where the ray meets its
// reflector again, 0 elsewhere (the supersampled fraction then comes out of the least
// squares). Composite: local.rgb + (1 - local.a) distant. Every map is linear in its texels,
// so each is one least-squares solve (inferPemMap); rays leaving a hull triangle
// (PemSample::onHull) never read the local layer and are left out of its rows. With pixel
// rows (PemInferOptions::rows) a pixel's local row is the mean over its off-hull sub-rays
// (its coverage target their fraction that meets the reflector again: antialiased alpha);
// with centre rows a pixel draws the local layer where its centre ray is off the hull, and
// its local row averages all its sub-rays (hull ones count as coverage 0), looked up at the
// centre ray as the rasteriser does.
#include "assetcooker/lib/flavours/pem/pem_infer.h"
#include "components/reflection_probe/pem/pem_asset.h"

#include <glm/vec3.hpp>

namespace specula {

// How many of the traced reflector rays see their own reflector again, and how many leave a
// triangle off the hull (the local layer's rows).
struct PemCoverage {
    std::size_t rays = 0;
    std::size_t offHull = 0;
    std::size_t selfHits = 0; // among the off-hull rays
    double fraction() const { return rays ? double(selfHits) / double(rays) : 0.0; }
};
PemCoverage pemCoverage(const PemSamples& samples);

// The sphere of the local layer, fitted to probe-local reflector points (the off-hull rays'
// x): the algebraic least-squares sphere |p|^2 = 2 c.p + k (for a bowl's spherical inside,
// the bowl's own sphere, so the lookup lands where the ray really meets the bowl again).
// Where that fit is ill-posed (fewer than four points, coplanar points, a radius past ten
// times the points' extent) the points' bounding sphere. Throws Error naming "local" when
// `points` is empty or not finite.
PemLocalSphere fitPemLocalSphere(const std::vector<glm::vec3>& points);

// The bounding sphere alone: the centre of the points' box, the farthest point's distance.
PemLocalSphere boundPemLocalSphere(const std::vector<glm::vec3>& points);

struct PemLayers {
    PemInference distant;
    PemInference local; // all zero (alpha 0) when no ray is off the hull: nothing to infer
    double seconds = 0; // wall time of the solves (the distant one beside the local one)
};

// The distant map from every sample (target: PemSample::distant off the hull, the full target
// on it, where nothing is drawn over the distant layer) with `distant`'s options;
// the local map from the off-hull samples (target: selfHit ? target : 0, alpha: selfHit) on
// `sphere` at localFaceRes with `local`'s regularisation and tolerance (its geometry, MIP
// levels and prior are replaced: one level, prior 0). Without an off-hull sample the local
// map is all zero (alpha 0: the distant layer alone).
PemLayers inferPemLayers(const PemSamples& samples, const PemInferOptions& distant,
                         const PemInferOptions& local, const PemLocalSphere& sphere);

} // namespace specula
