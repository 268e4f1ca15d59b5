// The distance flavour's entry point for a host's own fragment shader (DistanceHostProbe,
// distance_host_probe.h): the host prepends DistanceHostProbe::glslLibrary() (this file with
// its includes expanded, after the probe's permutation defines) and calls
//     vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// worldPos: the reflector point in world space; normal: its shading normal (any length; a zero
// or NaN normal falls back to the screen-space geometric one); viewDir: from the eye to the
// point; roughness: perceptual (0: a mirror). Returns the radiance the reflector reflects,
// before the host's Fresnel and albedo: with HAS_GLOSSY the GGX chain at the hit times the
// directional albedo. Specula's own reflector pass (distance_reflector.frag) calls it too. Samplers and the parameter block are bound by
// DistanceHostProbe::bindTo on units and a binding point the host chose.
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/math/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_probe_gpu.glsl"

uniform sampler2D uSky;
uniform int uHasSky;

vec3 fetchSky(vec3 dir) {
    return uHasSky != 0 ? textureLod(uSky, equirectUv(dir), 0.0).rgb : vec3(0.0);
}

#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"

#if HAS_GLOSSY
uniform int uChainLevels;
#include "components/reflection_probe/distance/shaders/distance_glossy_gpu.glsl"
#include "engine/math/cube_chain_sample.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_glossy_lookup.glsl.h"
uniform sampler2D uGgxAlbedo;
float fetchGgxAlbedo(int i, int j) { return texelFetch(uGgxAlbedo, ivec2(i, j), 0).r; }
#include "engine/image/ggx_albedo.glsl.h"
#endif

vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness) {
    vec3 x = worldPos - probeCentre();
    vec3 v = normalize(viewDir);
    vec3 geometric = normalize(cross(dFdx(worldPos), dFdy(worldPos)));
    vec3 n = safeNormal(normal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));
    DistanceParams p = lookupParams();
#if HAS_GLOSSY
    // The glossy variant runs the chain's path at every roughness (0 reads level 0: the
    // mirror's radiance, CpuDistanceProbe::glossySample).
    float r = max(roughness, 0.0);
    return probeGlossySample(x, lhat, r, p, uChainLevels).radiance * ggxAlbedo(abs(dot(n, v)), r);
#else
    int fetches = 0;
    return probeRadiance(x, lhat, p, fetches);
#endif
}
