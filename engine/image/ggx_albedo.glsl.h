// Shared by GLSL and C++ (see engine/core/glsl_host.h): the directional albedo E of a GGX
// microfacet surface with F = 1, E(n.v, roughness) = integral of D G2 / (4 n.l n.v) (n.l)
// over the hemisphere: the share of the light a rough mirror reflects at all (the rest is
// lost to masking and below the horizon). A prefiltered chain is normalised (each level
// averages radiance); the reflected light is that average times E. Read bilinearly from a
// kGgxAlbedoSize^2 table whose entry (i, j) holds n.v = i / (size - 1) and perceptual
// roughness j / (size - 1), both ends included (engine/image/ggx_albedo.h computes it); the
// includer provides float fetchGgxAlbedo(int i, int j).
#ifndef SPECULA_GGX_ALBEDO_GLSL_H
#define SPECULA_GGX_ALBEDO_GLSL_H

SHARED_CONST int kGgxAlbedoSize = 32;

float ggxAlbedo(float nv, float roughness) {
    float fx = clamp(nv, 0.0f, 1.0f) * float(kGgxAlbedoSize - 1);
    float fy = clamp(roughness, 0.0f, 1.0f) * float(kGgxAlbedoSize - 1);
    float x0 = floor(fx);
    float y0 = floor(fy);
    float ax = fx - x0;
    float ay = fy - y0;
    int i0 = clamp(int(x0), 0, kGgxAlbedoSize - 1);
    int j0 = clamp(int(y0), 0, kGgxAlbedoSize - 1);
    int i1 = clamp(int(x0) + 1, 0, kGgxAlbedoSize - 1);
    int j1 = clamp(int(y0) + 1, 0, kGgxAlbedoSize - 1);
    float bottom = mix(fetchGgxAlbedo(i0, j0), fetchGgxAlbedo(i1, j0), ax);
    float top = mix(fetchGgxAlbedo(i0, j1), fetchGgxAlbedo(i1, j1), ax);
    return mix(bottom, top, ay);
}

#endif
