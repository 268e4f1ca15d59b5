// Reflector pixels of a parameterized-environment-map probe: the lookup of the two samples
// the parameter block names, mixed by its weight (texel by texel: one lookup). Defines: GEOMETRY_DISTANCE (0 the box
// lookup, pem_lookup.glsl.h; 1 the distance-rectified one, pem_distance_lookup.glsl.h),
// HAS_FRESNEL (0/1), OUTPUT (0 colour, 1 probe-local position, 2 reflected direction: inputs
// for the CPU twin).
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
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
out vec4 fragColor;

// The lookup is linear in the texels, so blending the two samples' texels as they are fetched
// equals blending the two lookups (the CPU twin blends lookups): one search, not two, for the
// same ray and the same geometry.
vec3 fetchTexel(int face, int i, int j) {
    vec3 a = texelFetch(uPemMaps, ivec3(i, j, uPem.layerA + face), 0).rgb;
    if (uPem.wb <= 0.0) return a;
    return mix(a, texelFetch(uPemMaps, ivec3(i, j, uPem.layerB + face), 0).rgb, uPem.wb);
}

#include "components/reflection_probe/pem/shaders/pem_lookup.glsl.h"

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

void main() {
    // Probe-local space: the lookup never sees world coordinates.
    vec3 x = vWorldPos - uPem.centre;
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));

    vec3 colour = blendedRadiance(x, lhat);
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
