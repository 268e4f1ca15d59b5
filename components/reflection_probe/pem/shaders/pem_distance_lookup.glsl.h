// Shared by GLSL and C++ (see engine/core/glsl_host.h): the lookup of a parameterized
// environment map with DISTANCE geometry. Box geometry (pem_lookup.glsl.h) puts everything
// on the map box, so off the sampled viewpoints objects inside the box (columns, a table)
// land in the wrong place and two neighbouring maps ghost when blended. Here the reflected
// ray is rectified against a distance cube captured at the map centre by the distance
// flavour's own search (distance_lookup.glsl.h, secant on its single composite layer), and
// the direction of the point it finds indexes the PEM map through the same filter (per-face
// bilinear, trilinear across MIP levels) as the box lookup. The distance cube only picks
// WHICH texels are read, so the result stays linear in the map's texels and the cooker
// measures the rendering matrix's rows exactly as for box geometry.
//
// The includer provides, before including this file (GLSL needs declarations first):
//   cubeFaceUv, pem_lookup.glsl.h (pemFetchMap, hence fetchTexel and its MIP hooks),
//   distance_lookup_types.glsl.h (DistanceParams, kMethodSecant),
//   float fetchDistanceTexel(int face, int i, int j)   the distance cube, level 0
//   int pemMapFaceRes()        texels along a face edge of the PEM map
//   int pemDistanceFaceRes()   texels along a face edge of the distance cube
#ifndef SPECULA_PEM_DISTANCE_LOOKUP_GLSL_H
#define SPECULA_PEM_DISTANCE_LOOKUP_GLSL_H

// Nearest texel of the distance cube, clamped to the face: never filtered, as the distance
// flavour reads it (a blend of a distance and d_inf across a silhouette means nothing).
float fetchDistance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    int n = pemDistanceFaceRes();
    int i = clamp(int(f.x * float(n)), 0, n - 1);
    int j = clamp(int(f.y * float(n)), 0, n - 1);
    return fetchDistanceTexel(int(f.z), i, j);
}

// The PEM map at the direction of the point found (or of the ray, where the cube sees
// nothing): both read the map itself, so every texel the lookup reads is inferable.
vec3 fetchRadiance(int layer, vec3 dir) {
    return pemFetchMap(cubeFaceUv(dir), pemMapFaceRes());
}

vec3 fetchSky(vec3 dir) {
    return pemFetchMap(cubeFaceUv(dir), pemMapFaceRes());
}

// The single-layer secant search only: every other method compiles out.
#define HAS_ENVMAP 0
#define HAS_BOXPROJ 0
#define HAS_BISECTION 0
#define HAS_SECANT 1
#define HAS_AVGDIST 0
#define HAS_MARCH 0
#define HAS_LAYERS 0
#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
#undef HAS_ENVMAP
#undef HAS_BOXPROJ
#undef HAS_BISECTION
#undef HAS_SECANT
#undef HAS_AVGDIST
#undef HAS_MARCH
#undef HAS_LAYERS

// The search parameters of a PEM distance geometry as the distance lookup takes them; the
// box fields and layers are unused by the single-layer secant.
DistanceParams pemDistanceParams(float dInf, float range, float tolerance, int maxSteps) {
    DistanceParams p;
    p.boxMin = vec3(0.0f);
    p.range = range;
    p.boxMax = vec3(0.0f);
    p.tolerance = tolerance;
    p.centre = vec3(0.0f);
    p.dInf = dInf;
    p.maxSteps = maxSteps;
    p.method = kMethodSecant;
    p.layerCount = 0;
    p.faceRes = pemDistanceFaceRes();
    return p;
}

// Radiance the map holds for the reflected ray x + t l (x probe-local, l unit).
vec3 pemDistanceRadiance(vec3 x, vec3 l, DistanceParams p) {
    int fetches = 0;
    return probeRadiance(x, l, p, fetches);
}

#endif
