// Shared by GLSL and C++ (see engine/core/glsl_host.h).
// Cube-face mapping with OpenGL's face order (+X -X +Y -Y +Z -Z) and orientation. We do the
// mapping ourselves (cube maps are stored as 6-layer 2D arrays) so the GPU and the CPU twin
// pick the same face on ties: X wins over Y, Y over Z. A zero or NaN direction maps to the
// centre of +X instead of propagating NaN into a texel index.
#ifndef SPECULA_CUBE_FACE_GLSL_H
#define SPECULA_CUBE_FACE_GLSL_H

// Returns (u, v, face) with u, v in [0, 1]; v = 0 is the face's first stored row.
vec3 cubeFaceUv(vec3 dir) {
    if (any(isnan(dir))) return vec3(0.5f, 0.5f, 0.0f);
    // Infinite components dominate: keep their signs, drop the finite ones (inf/inf is NaN).
    if (any(isinf(dir))) dir = mix(vec3(0.0f), sign(dir), isinf(dir));
    vec3 a = abs(dir);
    float ma;
    float sc;
    float tc;
    float face;
    if (a.x >= a.y && a.x >= a.z) {
        ma = a.x;
        face = dir.x >= 0.0f ? 0.0f : 1.0f;
        sc = dir.x >= 0.0f ? -dir.z : dir.z;
        tc = -dir.y;
    } else if (a.y >= a.z) {
        ma = a.y;
        face = dir.y >= 0.0f ? 2.0f : 3.0f;
        sc = dir.x;
        tc = dir.y >= 0.0f ? dir.z : -dir.z;
    } else {
        ma = a.z;
        face = dir.z >= 0.0f ? 4.0f : 5.0f;
        sc = dir.z >= 0.0f ? dir.x : -dir.x;
        tc = -dir.y;
    }
    if (!(ma > 0.0f)) return vec3(0.5f, 0.5f, 0.0f); // zero direction

    // Divide before halving: 0.5 / ma overflows for denormal ma, and 0 * inf is NaN.
    return vec3(clamp(0.5f * (sc / ma) + 0.5f, 0.0f, 1.0f),
                clamp(0.5f * (tc / ma) + 0.5f, 0.0f, 1.0f), face);
}

// Inverse of cubeFaceUv: the (unnormalised) direction through (u, v) of `face`.
vec3 cubeFaceDirection(int face, vec2 uv) {
    float sc = uv.x * 2.0f - 1.0f;
    float tc = uv.y * 2.0f - 1.0f;
    if (face == 0) return vec3(1.0f, -tc, -sc);
    if (face == 1) return vec3(-1.0f, -tc, sc);
    if (face == 2) return vec3(sc, 1.0f, tc);
    if (face == 3) return vec3(sc, -1.0f, -tc);
    if (face == 4) return vec3(sc, -tc, 1.0f);
    return vec3(-sc, -tc, -1.0f);
}

#endif
