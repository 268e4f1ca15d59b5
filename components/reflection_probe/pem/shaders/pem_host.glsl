// The PEM flavour's entry point for a host's own fragment shader (PemHostProbe,
// pem_host_probe.h): the host prepends PemHostProbe::glslLibrary() (this file with its includes
// expanded, after the asset's GEOMETRY_DISTANCE and PEM_MIP defines) and calls
//     vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// worldPos: the reflector point in world space; normal: its shading normal (any length; a zero
// or NaN normal falls back to the screen-space geometric one); viewDir: from the eye to the
// point; roughness: unused (PEM maps are mirror reflections: inferred from the scene's own
// reflections, they hold the reflector's self- and inter-reflections at the cooked
// roughness). Returns the blend of the two samples nearest the parameter PemHostProbe::
// setSettings last gave, before the host's Fresnel. With PEM_MIP, call it in uniform control
// flow (it takes screen-space derivatives for the MIP level). Specula's own reflector pass
// (pem_reflector.frag) calls it too, and adds the local layer over it where the asset has one.
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

// The lookup is linear in the texels, so blending the two samples' texels as they are fetched
// equals blending the two lookups (the CPU twin blends lookups): one search, not two, for the
// same ray and the same geometry.
vec3 fetchTexel(int level, int face, int i, int j) {
    vec3 a = texelFetch(uPemMaps, ivec3(i, j, uPem.layerA + face), level).rgb;
    if (uPem.wb <= 0.0) return a;
    return mix(a, texelFetch(uPemMaps, ivec3(i, j, uPem.layerB + face), level).rgb, uPem.wb);
}

#if PEM_MIP
// Set once per pixel in speculaReflect, where control flow is uniform, from fine derivatives:
// the lookup may run inside the distance search's loop, where derivatives are undefined.
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

vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness) {
    // Probe-local space: the lookup never sees world coordinates.
    vec3 x = worldPos - uPem.centre;
    vec3 v = normalize(viewDir);
    vec3 geometric = normalize(cross(dFdx(worldPos), dFdy(worldPos)));
    vec3 n = safeNormal(normal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));
#if PEM_MIP
    gPemLod = pemFootprintLod(x, lhat, dFdxFine(x), dFdyFine(x), dFdxFine(lhat), dFdyFine(lhat),
                              uPem.boxMin, uPem.boxMax, uPem.faceRes);
#endif
    return blendedRadiance(x, lhat);
}
