// Shared by GLSL and C++ (see engine/core/glsl_host.h): the LOCAL layer of a parameterized
// environment map (Hakura, Snyder, Lengyel 2001, §4 "Layered EMs"; docs/design.md §5b). What a
// concave reflector shows of itself (the ray leaves it and meets it again) moves with the
// reflector, not with the environment, so it lives on a sphere fitted to the reflector: the
// reflected ray x + t l meets that sphere at its far intersection, and the direction from the
// sphere's centre to that point indexes a cube of RGBA texels, premultiplied radiance and
// coverage alpha. A reflector point on the fitted sphere whose ray comes back to the
// reflector reads, through this geometry, the texel of the very point it hits.
//
// The includer provides cubeFaceUv and
//   vec4 fetchLocalTexel(int face, int i, int j)   premultiplied RGB, alpha; level 0
// The lookup stays linear in the fetched texels (one bilinear of four), so the cooker measures
// its rendering matrix as it does the distant map's (pem_lookup_cpu.cpp).
#ifndef SPECULA_PEM_LOCAL_LOOKUP_GLSL_H
#define SPECULA_PEM_LOCAL_LOOKUP_GLSL_H

#include "components/reflection_probe/pem/shaders/pem_taps.glsl.h"

// Distance along l (unit) from x to the far intersection with the sphere (c, r). From inside
// the sphere that is the only forward one; from outside it is the exit of a ray that crosses
// the sphere. A ray that misses it (only from outside) takes its closest approach, so the
// result is finite and never negative.
float pemSphereFar(vec3 x, vec3 l, vec3 c, float r) {
    vec3 o = x - c;
    float b = dot(o, l);
    float q = dot(o, o) - r * r;
    float disc = max(b * b - q, 0.0f);
    return max(sqrt(disc) - b, 0.0f);
}

// pemFetchBilinear's filter (the same taps) on the RGBA local cube, level 0.
vec4 pemLocalFetchBilinear(vec3 faceUv, int faceRes) {
    PemTaps t = pemBilinearTaps(faceUv, faceRes);
    vec4 top = (1.0f - t.a.x) * fetchLocalTexel(t.face, t.i0, t.j0) +
               t.a.x * fetchLocalTexel(t.face, t.i1, t.j0);
    vec4 bottom = (1.0f - t.a.x) * fetchLocalTexel(t.face, t.i0, t.j1) +
                  t.a.x * fetchLocalTexel(t.face, t.i1, t.j1);
    return (1.0f - t.a.y) * top + t.a.y * bottom;
}

// Premultiplied local radiance and coverage for the reflected ray x + t l (x probe-local, l
// unit), the sphere (c, r) probe-local.
vec4 pemLocalRadiance(vec3 x, vec3 l, vec3 c, float r, int faceRes) {
    vec3 hit = x + pemSphereFar(x, l, c, r) * l;
    return pemLocalFetchBilinear(cubeFaceUv(hit - c), faceRes);
}

// The two layers composited: the local layer over the distant one (premultiplied "over").
vec3 pemComposite(vec4 local, vec3 distant) {
    return vec3(local) + (1.0f - local.a) * distant;
}

#endif
