// Shared by GLSL and C++ (see engine/core/glsl_host.h): the MIP level a PEM lookup reads,
// computed from the pixel's footprint rather than left to the texture unit, whose level
// selection is implementation-defined: the shader and its CPU twin (the rows of the
// cooker's rendering matrix) must read the same levels with the same weights.
//
// The footprint: the fine screen derivatives of the probe-local reflector point x and of the
// unit reflected direction l (dFdxFine / dFdyFine in the shader; the quad twin,
// reflector_pixels.h, on the CPU), carried through the map box's hit p = x + t l to the cube
// face coordinate by the chain rule, in texels of level 0. Distance-geometry maps use the
// same box estimate: the level is a footprint estimate, and the inference fits the texels to
// whichever level this picks.
#ifndef SPECULA_PEM_LOD_GLSL_H
#define SPECULA_PEM_LOD_GLSL_H

// Level-0 texel offset of the cube face coordinate for the move dp of the point p (p and
// dp probe-local, p off the origin): the face of p's major axis, its two other coordinates
// over the major one, scaled to texels (a face spans 2 units at unit distance).
vec2 pemFaceDelta(vec3 p, vec3 dp, int faceRes) {
    vec3 q = abs(p);
    int m = q.x >= q.y && q.x >= q.z ? 0 : (q.y >= q.z ? 1 : 2);
    int u = m == 0 ? 1 : 0;
    int v = m == 2 ? 1 : 2;
    float inv = 1.0f / max(q[m], 1e-20f);
    float su = (dp[u] - p[u] / p[m] * dp[m]) * inv;
    float sv = (dp[v] - p[v] / p[m] * dp[m]) * inv;
    return 0.5f * float(faceRes) * vec2(su, sv);
}

// The box hit's move for the moves dx, dl: t is the distance to the exit wall (axis k), so
// dt = -(dx_k + t dl_k) / l_k and dp = dx + t dl + dt l.
vec3 pemBoxHitDelta(vec3 x, vec3 l, vec3 dx, vec3 dl, vec3 boxMin, vec3 boxMax) {
    vec3 wall = mix(boxMin, boxMax, step(vec3(0.0f), l));
    float t = 3.0e38f;
    int k = 0;
    for (int c = 0; c < 3; ++c) {
        if (l[c] != 0.0f) {
            float tc = (wall[c] - x[c]) / l[c];
            if (tc < t) {
                t = tc;
                k = c;
            }
        }
    }
    t = max(t, 0.0f);
    float dt = -(dx[k] + t * dl[k]) / l[k];
    return dx + t * dl + dt * l;
}

// log2 of the longer screen axis's footprint in level-0 texels (GL's rho), before clamping:
// below 0 the map is magnified and level 0 is read.
float pemFootprintLod(vec3 x, vec3 l, vec3 dxdX, vec3 dxdY, vec3 dldX, vec3 dldY, vec3 boxMin,
                      vec3 boxMax, int faceRes) {
    vec3 p = x + pemBoxExit(x, l, boxMin, boxMax) * l;
    vec2 gx = pemFaceDelta(p, pemBoxHitDelta(x, l, dxdX, dldX, boxMin, boxMax), faceRes);
    vec2 gy = pemFaceDelta(p, pemBoxHitDelta(x, l, dxdY, dldY, boxMin, boxMax), faceRes);
    float rho = max(length(gx), length(gy));
    return log2(max(rho, 1e-20f));
}

#endif
