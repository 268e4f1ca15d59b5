// Shared by GLSL and C++ (see engine/core/glsl_host.h): the lookup of a parameterized
// environment map (Hakura, Snyder, Lengyel 2001; docs/design.md §5b) with box geometry. The C++
// copy is both the CPU twin of the shader and, with fetches that record instead of read, the row of
// the rendering matrix the cooker infers the map from: display and inference are one code.
//
// Positions are probe-local; the map's centre is the origin. The includer provides
//   cubeFaceUv (engine/math/cube_face.glsl.h) and
//   vec3 fetchTexel(int level, int face, int i, int j)   texel (column i, row j; row 0 first
//                       stored) of `face` at MIP level `level`, 0 <= i, j < max(faceRes >> level,
//                       1)
// and, when PEM_MIP is 1 (the map has more than one level),
//   float pemLookupLod()   the pixel's level of detail (pem_lod.glsl.h's pemFootprintLod)
//   int pemMapLevels()     the map's MIP levels
// The lookup must stay linear in the fetched texels: the cooker measures its weights by
// feeding it unit texels (pem_lookup_cpu.cpp).
#ifndef SPECULA_PEM_LOOKUP_GLSL_H
#define SPECULA_PEM_LOOKUP_GLSL_H

#include "components/reflection_probe/pem/shaders/pem_taps.glsl.h"

// Distance along l from x (inside the box) to the wall the ray leaves through. Axes with a
// zero component are skipped; a unit l has a component of at least 1/sqrt(3), so the result
// is finite and never negative (a point outside the box is not refused).
float pemBoxExit(vec3 x, vec3 l, vec3 boxMin, vec3 boxMax) {
    vec3 wall = mix(boxMin, boxMax, step(vec3(0.0f), l)); // the wall each axis heads for
    float t = 3.0e38f;
    for (int k = 0; k < 3; ++k) {
        if (l[k] != 0.0f) t = min(t, (wall[k] - x[k]) / l[k]);
    }
    return max(t, 0.0f);
}

// Bilinear within one face of MIP level `level` (faceRes its texels along an edge), four
// fetches with pem_taps.glsl.h's weights.
vec3 pemFetchBilinear(vec3 faceUv, int faceRes, int level) {
    PemTaps t = pemBilinearTaps(faceUv, faceRes);
    vec3 top = (1.0f - t.a.x) * fetchTexel(level, t.face, t.i0, t.j0) +
               t.a.x * fetchTexel(level, t.face, t.i1, t.j0);
    vec3 bottom = (1.0f - t.a.x) * fetchTexel(level, t.face, t.i0, t.j1) +
                  t.a.x * fetchTexel(level, t.face, t.i1, t.j1);
    return (1.0f - t.a.y) * top + t.a.y * bottom;
}

// The map read at a cube face coordinate. PEM_MIP: trilinear between the two levels around
// the pixel's lod (pemLookupLod, clamped to the asset's levels), each level's own bilinear;
// a whole lod reads one level, exactly as a single-level map does. Without PEM_MIP: level 0.
vec3 pemFetchMap(vec3 faceUv, int faceRes) {
#if PEM_MIP
    float lod = clamp(pemLookupLod(), 0.0f, float(pemMapLevels() - 1));
    int l0 = int(floor(lod));
    float a = lod - float(l0);
    vec3 c0 = pemFetchBilinear(faceUv, max(faceRes >> l0, 1), l0);
    if (a <= 0.0f) return c0;
    int l1 = min(l0 + 1, pemMapLevels() - 1);
    return (1.0f - a) * c0 + a * pemFetchBilinear(faceUv, max(faceRes >> l1, 1), l1);
#else
    return pemFetchBilinear(faceUv, faceRes, 0);
#endif
}

// Radiance the map holds for the reflected ray x + t l (l unit): the ray meets the map's box,
// and the direction from the map centre to that point indexes the cube (Hakura §4, "box
// maps").
vec3 pemRadiance(vec3 x, vec3 l, vec3 boxMin, vec3 boxMax, int faceRes) {
    vec3 hit = x + pemBoxExit(x, l, boxMin, boxMax) * l;
    return pemFetchMap(cubeFaceUv(hit), faceRes);
}

#endif
