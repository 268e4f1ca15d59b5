// Shared by GLSL and C++ (see engine/core/glsl_host.h): where the four texels of a bilinear
// read within one cube face lie and how they mix. Both PEM layers (pem_lookup.glsl.h, RGB;
// pem_local_lookup.glsl.h, RGBA) filter alike; only their fetches differ, so the taps are
// computed once here and each layer does its own four fetches with them.
#ifndef SPECULA_PEM_TAPS_GLSL_H
#define SPECULA_PEM_TAPS_GLSL_H

// Columns i0, i1 and rows j0, j1 of `face`, and the weight a of the second of each pair:
// what a GL_LINEAR, CLAMP_TO_EDGE fetch from one layer of a 2D array reads (texel centres at
// (i + 0.5) / N), clamped to the face edge, with weights that are ours rather than the
// filtering hardware's 8-bit fractions.
struct PemTaps {
    int face;
    int i0;
    int j0;
    int i1;
    int j1;
    vec2 a;
};

PemTaps pemBilinearTaps(vec3 faceUv, int faceRes) {
    PemTaps t;
    t.face = int(faceUv.z);
    vec2 f = vec2(faceUv.x, faceUv.y) * float(faceRes) - vec2(0.5f);
    vec2 f0 = floor(f);
    t.a = f - f0;
    int i0 = int(f0.x);
    int j0 = int(f0.y);
    t.i1 = min(i0 + 1, faceRes - 1);
    t.j1 = min(j0 + 1, faceRes - 1);
    t.i0 = max(i0, 0);
    t.j0 = max(j0, 0);
    return t;
}

#endif
