// Shared by GLSL and C++ (see engine/core/glsl_host.h).
// The house shading of environment surfaces: view-independent, so a probe baked from its
// centre sees the same radiance a ray-traced reflection sees. Base colour lit by a
// constant ambient term plus one directional sun, no shadows.
#ifndef SPECULA_SHADING_GLSL_H
#define SPECULA_SHADING_GLSL_H

vec3 sunDirection() {
    return vec3(0.40824829f, 0.81649658f, 0.40824829f);
}

vec3 shadeSurface(vec3 albedo, vec3 normal) {
    float lambert = max(dot(normal, sunDirection()), 0.0f);
    return albedo * (0.35f + 0.65f * lambert);
}

// Equirectangular panorama coordinates for a world direction: u grows with azimuth
// measured from -Z towards +X, v = 0 is straight up (row 0 of the image is the zenith).
vec2 equirectUv(vec3 dir) {
    float u = 0.5f + atan(dir.x, -dir.z) * 0.15915494f;
    float v = acos(clamp(dir.y, -1.0f, 1.0f)) * 0.31830989f;
    return vec2(u, v);
}

#endif
