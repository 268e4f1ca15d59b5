// Shared by GLSL and C++ (see engine/core/glsl_host.h): the lookup of a parameterized
// environment map (Hakura, Snyder, Lengyel 2001; DESIGN §5b) with box geometry. The C++ copy
// is both the CPU twin of the shader and, with fetches that record instead of read, the row
// of the rendering matrix the cooker infers the map from: display and inference are one code.
//
// Positions are probe-local; the map's centre is the origin. The includer provides
//   cubeFaceUv (engine/math/cube_face.glsl.h) and
//   vec3 fetchTexel(int face, int i, int j)   texel (column i, row j; row 0 first stored) of
//                                            `face`, 0 <= i, j < faceRes, level 0
// The lookup must stay linear in the fetched texels: the cooker measures its weights by
// feeding it unit texels (pem_lookup_cpu.cpp).
#ifndef SPECULA_PEM_LOOKUP_GLSL_H
#define SPECULA_PEM_LOOKUP_GLSL_H

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

// Bilinear within one face, clamped to the face edge: what a GL_LINEAR, CLAMP_TO_EDGE fetch
// from one layer of a 2D array reads (texel centres at (i + 0.5) / N), written out as four
// fetches so the weights are ours, not the filtering hardware's 8-bit fractions.
// Level 0 only: the paper's MIP levels (all inferred together) are not built yet (issue 12).
vec3 pemFetchBilinear(vec3 faceUv, int faceRes) {
    int face = int(faceUv.z);
    vec2 f = vec2(faceUv.x, faceUv.y) * float(faceRes) - vec2(0.5f);
    vec2 f0 = floor(f);
    vec2 a = f - f0;
    int i0 = int(f0.x);
    int j0 = int(f0.y);
    int i1 = min(i0 + 1, faceRes - 1);
    int j1 = min(j0 + 1, faceRes - 1);
    i0 = max(i0, 0);
    j0 = max(j0, 0);
    vec3 top = (1.0f - a.x) * fetchTexel(face, i0, j0) + a.x * fetchTexel(face, i1, j0);
    vec3 bottom = (1.0f - a.x) * fetchTexel(face, i0, j1) + a.x * fetchTexel(face, i1, j1);
    return (1.0f - a.y) * top + a.y * bottom;
}

// Radiance the map holds for the reflected ray x + t l (l unit): the ray meets the map's box,
// and the direction from the map centre to that point indexes the cube (Hakura §4, "box
// maps").
vec3 pemRadiance(vec3 x, vec3 l, vec3 boxMin, vec3 boxMax, int faceRes) {
    vec3 hit = x + pemBoxExit(x, l, boxMin, boxMax) * l;
    return pemFetchBilinear(cubeFaceUv(hit), faceRes);
}

#endif
