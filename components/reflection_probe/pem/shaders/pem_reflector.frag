// Reflector pixels of a parameterized-environment-map probe: the lookup of the two samples
// the parameter block names, mixed by its weight (texel by texel: one lookup). Defines: GEOMETRY_DISTANCE (0 the box
// lookup, pem_lookup.glsl.h; 1 the distance-rectified one, pem_distance_lookup.glsl.h),
// HAS_FRESNEL (0/1), PEM_MIP (0/1: the distant maps have MIP levels, read trilinear at the
// level the pixel's footprint picks, pem_lod.glsl.h), HAS_LOCAL_LAYER (0/1: the local layer over the distant one, off the
// reflector's hull; pem_local_lookup.glsl.h), OUTPUT (0 colour, 1 probe-local position, 2
// reflected direction, 3 the hull flag in red, 4 the MIP level of detail in red, 0 without
// PEM_MIP: inputs for the CPU twin).
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"
#include "components/reflection_probe/pem/shaders/pem_params.glsl.h"

layout(std140, binding = kPemParamsBinding) uniform PemParamsUniforms {
    PemParams uPem;
};
// Sample s's faces are array layers 6s .. 6s+5; RGB radiance, NEAREST filtering: the lookup
// does its own bilinear through fetchTexel, as the twin does.
uniform sampler2DArray uPemMaps;
#if GEOMETRY_DISTANCE
// The distance cube: six R32F layers, read nearest with texelFetch as the twin reads it.
uniform sampler2DArray uPemDistance;
#endif
#if HAS_LOCAL_LAYER
// Premultiplied RGB and coverage per texel, layered as uPemMaps.
uniform sampler2DArray uPemLocal;
// One bit per triangle of the drawn reflector, all its primitives in order (pem_hull.h); this
// draw's first triangle is bit uPemHullBase (gl_PrimitiveID restarts at each draw).
layout(std430, binding = kPemHullBinding) readonly buffer PemHullFlags {
    uint uPemHullBits[];
};
uniform int uPemHullBase;
#endif
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
out vec4 fragColor;

// The lookup is linear in the texels, so blending the two samples' texels as they are fetched
// equals blending the two lookups (the CPU twin blends lookups): one search, not two, for the
// same ray and the same geometry.
vec3 fetchTexel(int level, int face, int i, int j) {
    vec3 a = texelFetch(uPemMaps, ivec3(i, j, uPem.layerA + face), level).rgb;
    if (uPem.wb <= 0.0) return a;
    return mix(a, texelFetch(uPemMaps, ivec3(i, j, uPem.layerB + face), level).rgb, uPem.wb);
}

#if PEM_MIP
// Set once per pixel in main, where control flow is uniform, from fine derivatives: the
// lookup may run inside the distance search's loop, where derivatives are undefined.
float gPemLod = 0.0;
float pemLookupLod() {
    return gPemLod;
}
int pemMapLevels() {
    return uPem.mapLevels;
}
#endif

#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"
#if PEM_MIP
#include "components/reflection_probe/pem/shaders/pem_lod.glsl.h"
#endif

#if GEOMETRY_DISTANCE
#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"

float fetchDistanceTexel(int face, int i, int j) {
    return texelFetch(uPemDistance, ivec3(i, j, face), 0).r;
}
int pemMapFaceRes() {
    return uPem.faceRes;
}
int pemDistanceFaceRes() {
    return uPem.distanceFaceRes;
}

#include "components/reflection_probe/pem/shaders/pem_distance_lookup.glsl.h"
#endif

vec3 blendedRadiance(vec3 x, vec3 l) {
#if GEOMETRY_DISTANCE
    DistanceParams p = pemDistanceParams(uPem.dInf, uPem.range, uPem.tolerance, uPem.maxSteps);
    return pemDistanceRadiance(x, l, p);
#else
    return pemRadiance(x, l, uPem.boxMin, uPem.boxMax, uPem.faceRes);
#endif
}

#if HAS_LOCAL_LAYER
// The two samples blended texel by texel, as fetchTexel does the distant maps.
vec4 fetchLocalTexel(int face, int i, int j) {
    vec4 a = texelFetch(uPemLocal, ivec3(i, j, uPem.layerA + face), 0);
    if (uPem.wb <= 0.0) return a;
    return mix(a, texelFetch(uPemLocal, ivec3(i, j, uPem.layerB + face), 0), uPem.wb);
}

#include "components/reflection_probe/pem/shaders/pem_local_lookup.glsl.h"

bool onHull() {
    int k = uPemHullBase + gl_PrimitiveID;
    return ((uPemHullBits[k >> 5] >> uint(k & 31)) & 1u) != 0u;
}
#endif

void main() {
    // Probe-local space: the lookup never sees world coordinates.
    vec3 x = vWorldPos - uPem.centre;
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));
#if PEM_MIP
    gPemLod = pemFootprintLod(x, lhat, dFdxFine(x), dFdyFine(x), dFdxFine(lhat), dFdyFine(lhat),
                              uPem.boxMin, uPem.boxMax, uPem.faceRes);
#endif

    vec3 colour = blendedRadiance(x, lhat);
    float hull = 1.0;
#if HAS_LOCAL_LAYER
    // Hull triangles never see the reflector: the distant layer alone (alpha 0).
    if (!onHull()) {
        hull = 0.0;
        colour = pemComposite(
            pemLocalRadiance(x, lhat, uPem.localCentre, uPem.localRadius, uPem.localFaceRes),
            colour);
    }
#endif
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#elif OUTPUT == 3
    fragColor = vec4(hull, 0.0, 0.0, 1.0);
#elif OUTPUT == 4
#if PEM_MIP
    fragColor = vec4(gPemLod, 0.0, 0.0, 1.0);
#else
    fragColor = vec4(0.0, 0.0, 0.0, 1.0);
#endif
#else
    fragColor = vec4(colour, 1.0);
#endif
}
