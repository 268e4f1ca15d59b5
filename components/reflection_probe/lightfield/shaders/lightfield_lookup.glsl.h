// Shared by GLSL and C++ (see engine/core/glsl_host.h): the light-field-slab lookup of Yu,
// Yang, McMillan 2005 (docs/design.md §5). The C++ copy is the CPU twin the tests hold the shader
// to.
//
// Positions are cell-local (origin at the cell centre). The atlas layout is described in
// components/reflection_probe/lightfield/lightfield_asset.h. The includer provides:
//   vec3  fetchAtlas(int slab, vec2 texel)   bilinear RGB of layer `slab` at atlas texel
//                                            coordinates (texel centres at i + 0.5)
//   float slabDisparity(int slab)            focal-plane disparity, pixels per camera step
#ifndef SPECULA_LIGHTFIELD_LOOKUP_GLSL_H
#define SPECULA_LIGHTFIELD_LOOKUP_GLSL_H

struct LightFieldParams {
    float halfCell; // l / 2: the camera planes lie at +-halfCell on each axis
    int cameras;    // NUM per side (>= 2)
    int res;        // RES per camera image
};

struct SlabCoords {
    int slab;    // 0..5: +X -X +Y -Y +Z -Z
    vec2 camera; // continuous camera index along (b, c): [0, NUM-1] for rays from the cell
    vec2 pixel;  // continuous pixel index (texel centres at integers): [-0.5, RES-0.5]
    float along; // distance from p to the camera plane along the slab axis: [0, l] in the cell
};

// Picks the slab by the largest absolute direction component with the tie rule of
// cubeFaceUv (X over Y over Z), intersects the slab's camera plane (Yu eq. 4) and maps to
// continuous camera and pixel indices (eq. 1). One code path for all six slabs: the axis is
// an index into the vectors, not a branch per slab. A zero, infinite or NaN direction reads
// as +X, a non-finite position as the cell centre, so no NaN reaches an index.
SlabCoords slabCoords(vec3 p, vec3 d, LightFieldParams prm) {
    vec3 a = abs(d);
    bool badDir = any(isnan(d)) || any(isinf(d)) || !(max(a.x, max(a.y, a.z)) > 0.0f);
    d = badDir ? vec3(1.0f, 0.0f, 0.0f) : d;
    a = abs(d);
    p = (any(isnan(p)) || any(isinf(p))) ? vec3(0.0f) : p;
    int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    int b = axis == 2 ? 0 : axis + 1;
    int c = axis == 0 ? 2 : axis - 1;
    float sigma = d[axis] >= 0.0f ? 1.0f : -1.0f;
    // |d_b|, |d_c| <= |d_a| by the choice of axis, so the slope is in [-1, 1] exactly (a
    // correctly rounded quotient never exceeds 1) and D_a -> 0 cannot happen for the axis.
    vec2 slope = vec2(d[b], d[c]) / a[axis];
    // Distance from p to the camera plane along the axis: in [0, l] for p in the cell.
    float along = prm.halfCell - sigma * p[axis];
    vec2 st = vec2(p[b], p[c]) + along * slope; // in [-3l/2, 3l/2] for p in the cell
    SlabCoords r;
    r.slab = 2 * axis + (sigma < 0.0f ? 1 : 0);
    r.camera = (st / (6.0f * prm.halfCell) + 0.5f) * float(prm.cameras - 1);
    r.pixel = (slope + 1.0f) * (0.5f * float(prm.res)) - 0.5f;
    r.along = along;
    return r;
}

// Quadrilinear lookup (Yu eq. 5-6): the four nearest cameras, each sampled bilinearly at
// the pixel shifted by the focal-plane disparity. Exactly four bilinear fetches. The pixel
// is clamped to its camera's tile (texel centres 0 .. RES-1), so filtering never reads a
// neighbouring camera.
vec3 lightFieldRadiance(vec3 p, vec3 d, LightFieldParams prm) {
    SlabCoords sc = slabCoords(p, d, prm);
    float last = float(prm.cameras - 1);
    vec2 cam = clamp(sc.camera, vec2(0.0f), vec2(last));
    vec2 base = min(floor(cam), vec2(last - 1.0f));
    vec2 f = cam - base;
    float disparity = slabDisparity(sc.slab);
    float tileMax = float(prm.res - 1);
    vec3 sum = vec3(0.0f);
    for (int k = 0; k < 4; ++k) {
        vec2 corner = vec2(float(k & 1), float(k >> 1));
        vec2 camIndex = base + corner;
        // A point on the focal plane seen by camera camIndex moves by (cam - camIndex) camera
        // steps times the disparity.
        vec2 px = clamp(sc.pixel + (cam - camIndex) * disparity, vec2(0.0f), vec2(tileMax));
        vec2 w2 = mix(vec2(1.0f) - f, f, corner);
        sum += (w2.x * w2.y) * fetchAtlas(sc.slab, camIndex * float(prm.res) + px + 0.5f);
    }
    return sum;
}

#endif
