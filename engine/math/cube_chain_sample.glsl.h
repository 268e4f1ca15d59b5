// Shared by GLSL and C++ (see engine/core/glsl_host.h): a chain of cube maps (such as the
// GGX prefiltered chain of engine/image/ggx_prefilter.h) sampled at a direction and a
// fractional level, seam-free: bilinear within a face and across its edges, trilinear between
// levels. The C++ sampleChain runs this very code, so the prefilter's tests hold the shader's
// copy as well.
//
// The includer provides
//   vec3 fetchChainTexel(int level, int face, ivec2 texel)   one texel's RGB, texel in [0, n)^2
//   int  chainFaceRes(int level)                             n: texels along the level's face
// with faces in the OpenGL order and orientation of engine/math/cube_face.glsl.h.
//
// Texel centres lie at (i + 0.5) / n. A bilinear tap past a face's edge reads the texel of
// the neighbouring face through the tap's direction (the face's plane extended by a texel);
// past a corner, where three faces meet and the fourth tap has no texel, it reads the mean of
// the three corner texels (as seamless cube-map hardware does), so a sample is continuous over
// the whole sphere. No recursion (GLSL has none): the corner case calls the edge case.
#ifndef SPECULA_CUBE_CHAIN_SAMPLE_GLSL_H
#define SPECULA_CUBE_CHAIN_SAMPLE_GLSL_H

#include "engine/math/cube_face.glsl.h"

// Texel `texel` of `face` (n x n) with exactly one coordinate one texel past the face: the
// texel of the neighbouring face through the tap's direction.
vec3 chainTexelPastEdge(int level, int face, int n, ivec2 texel) {
    vec2 uv = (vec2(texel) + vec2(0.5f)) / float(n);
    vec3 uvf = cubeFaceUv(cubeFaceDirection(face, uv));
    ivec2 t = clamp(ivec2(floor(vec2(uvf.x, uvf.y) * float(n))), ivec2(0), ivec2(n - 1));
    return fetchChainTexel(level, int(uvf.z), t);
}

// Texel `texel` of `face` (n x n), each coordinate in [-1, n]: read across an edge where one
// lies past the face, the mean of the three corner texels where both do.
vec3 chainTexelAcross(int level, int face, int n, ivec2 texel) {
    bool inX = texel.x >= 0 && texel.x < n;
    bool inY = texel.y >= 0 && texel.y < n;
    if (inX && inY) return fetchChainTexel(level, face, texel);
    if (inX || inY) return chainTexelPastEdge(level, face, n, texel);
    ivec2 c = clamp(texel, ivec2(0), ivec2(n - 1));
    return (fetchChainTexel(level, face, c) +
            chainTexelPastEdge(level, face, n, ivec2(texel.x, c.y)) +
            chainTexelPastEdge(level, face, n, ivec2(c.x, texel.y))) /
           3.0f;
}

// Bilinear at (u, v) in [0, 1]^2 of `face` of one level, taps past the edges read across them.
vec3 chainBilinear(int level, int face, vec2 uv) {
    int n = chainFaceRes(level);
    float fx = uv.x * float(n) - 0.5f;
    float fy = uv.y * float(n) - 0.5f;
    float x0f = floor(fx);
    float y0f = floor(fy);
    float ax = fx - x0f;
    float ay = fy - y0f;
    // u, v in [0, 1] put x0, y0 in [-1, n - 1].
    int x0 = int(x0f);
    int y0 = int(y0f);
    vec3 top = mix(chainTexelAcross(level, face, n, ivec2(x0, y0)),
                   chainTexelAcross(level, face, n, ivec2(x0 + 1, y0)), ax);
    vec3 bottom = mix(chainTexelAcross(level, face, n, ivec2(x0, y0 + 1)),
                      chainTexelAcross(level, face, n, ivec2(x0 + 1, y0 + 1)), ax);
    return mix(top, bottom, ay);
}

// The chain of `levels` levels along dir (need not be normalised) at a fractional level,
// clamped to [0, levels - 1] (NaN reads level 0): bilinear in the two levels around it,
// blended linearly; a whole level reads that level alone.
vec3 sampleCubeChain(vec3 dir, float level, int levels) {
    int last = levels - 1;
    float lv = clamp(isnan(level) ? 0.0f : level, 0.0f, float(last));
    int l0 = min(int(lv), last);
    int l1 = min(l0 + 1, last);
    float blend = lv - float(l0);
    vec3 uvf = cubeFaceUv(dir);
    int face = int(uvf.z);
    vec2 uv = vec2(uvf.x, uvf.y);
    vec3 c0 = chainBilinear(l0, face, uv);
    if (!(blend > 0.0f) || l1 == l0) return c0;
    return mix(c0, chainBilinear(l1, face, uv), blend);
}

#endif
