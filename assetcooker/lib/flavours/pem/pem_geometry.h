#pragma once
// The cooker side of PEM distance geometry (PemDistanceGeometry,
// shaders/pem_distance_lookup.glsl.h): the environment's distance cube at the map centre,
// traced with Embree, and the search parameters the lookup runs with.
#include "components/reflection_probe/pem/pem_lookup_cpu.h"
#include "engine/raytrace/ground_truth.h"

#include <vector>

#include <glm/vec3.hpp>

namespace specula {

// Traces tracer.traceEnvironment(centre, dir) through every texel centre of a faceRes cube
// (glsl::cubeFaceDirection, mirrors excluded as the tracer's environment scene excludes
// them): the hit distance, dInf where the ray meets nothing. Rows in parallel, each texel
// written by one task: the same result every run. capturedRadiance (when not null) gets the
// radiance along each of those rays (the sky on a miss), in PemMap texel order
// (face*N*N + j*N + i): what an ordinary cube map captured at the centre holds, the prior
// PemInferOptions can fall back to when N equals the map's face resolution.
//
// Search parameters (choosePemDistanceSearch), from the largest distance hit, maxD:
//   range D = 1.05 maxD: the search spans (x, x + 2D l), which holds every hit of a reflector
//     point up to D from the centre (a hit lies at most |x| + maxD away); 5% covers the
//     farther points between texel centres.
//   tolerance d_e = 1e-3 D: a millimetre per metre of scene, well below a texel's footprint
//     (about 2D / N at the face centre, 0.03 D at N = 64), so the texel, not the tolerance,
//     limits where the search lands.
//   maxSteps = ceil(log2(2D / d_e)) = 11, what bisection needs to narrow the span to d_e
//     (the distance flavour's default rule, bisectionSteps); the secant usually stops sooner.
// A scene where nothing is hit gets D = 1 (any span: every texel reads dInf, the lookup falls
// back to the ray's direction).
// Throws Error naming "face_res" (1 .. 4096), "centre" (not finite) or "d_inf" (not finite,
// or not above 2.1 maxD: a real distance past dInf / 2 would read as "nothing here").
PemDistanceGeometry bakePemDistanceGeometry(const GroundTruthTracer& tracer, glm::vec3 centre,
                                            int faceRes, float dInf,
                                            std::vector<glm::vec3>* capturedRadiance);

// Sets g.range, g.tolerance and g.maxSteps from g.distances and g.dInf by the rule above
// (apart so that a distance cube from elsewhere, e.g. a closed form, gets the same search).
// Throws Error naming "d_inf" as the bake does.
void choosePemDistanceSearch(PemDistanceGeometry& g);

} // namespace specula
