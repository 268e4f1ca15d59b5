// Shared by GLSL and C++ (see engine/core/glsl_host.h): what every reflector pixel does
// before the probe lookup, so the CPU twin starts from the same reflected ray.
#ifndef SPECULA_REFLECTOR_COMMON_GLSL_H
#define SPECULA_REFLECTOR_COMMON_GLSL_H

// Asset normals can be zero or NaN (docs/design.md §7): fall back to the geometric normal.
vec3 safeNormal(vec3 n, vec3 geometric) {
    float len2 = dot(n, n);
    if (!(len2 > 1e-20f) || isnan(len2) || isinf(len2)) return geometric;
    return n * inversesqrt(len2);
}

// Mirror direction of the unit view ray `v` (eye to surface) about `n`, with the normal
// turned to face the eye so thin or inside-out reflectors still reflect.
vec3 mirrorDirection(vec3 v, vec3 n) {
    vec3 nf = dot(n, v) > 0.0f ? -n : n;
    return v - 2.0f * dot(v, nf) * nf;
}

// Schlick's approximation; cosTheta = |dot(n, -v)|.
float schlickFresnel(float f0, float cosTheta) {
    float m = clamp(1.0f - cosTheta, 0.0f, 1.0f);
    float m2 = m * m;
    return f0 + (1.0f - f0) * m2 * m2 * m;
}

#endif
