// A level of distance probes for a host's own fragment shader (DistanceLevelHostProbe,
// distance_level_host_probe.h): the host prepends DistanceLevelHostProbe::glslLibrary() (this
// file with its includes expanded, after the level's permutation defines) and calls
//     vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness)
// as with a single probe (distance_host.glsl): up to LEVEL_K of the level's probes blended per
// pixel among the candidates bindTo handed over, exactly as Specula's own level pass
// (distance_level_reflector.frag) blends them. With HAS_GLOSSY every probe's share is its glossy
// sample at `roughness` (0: the mirror), times the GGX directional albedo.
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/math/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_level_gpu.glsl"

uniform sampler2D uSky;
uniform int uHasSky;

vec3 fetchSky(vec3 dir) {
    return uHasSky != 0 ? textureLod(uSky, equirectUv(dir), 0.0).rgb : vec3(0.0);
}

#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_seen.glsl.h"

#if HAS_GLOSSY
uniform int uChainLevels; // every probe's chain's levels, the composite (level 0) included
float gRoughness;         // this pixel's roughness, read by every probe's lookup
#include "components/reflection_probe/distance/shaders/distance_level_glossy_gpu.glsl"
#include "engine/math/cube_chain_sample.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_glossy_lookup.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_glossy_seen.glsl.h"
uniform sampler2D uGgxAlbedo;
float fetchGgxAlbedo(int i, int j) { return texelFetch(uGgxAlbedo, ivec2(i, j), 0).r; }
#include "engine/image/ggx_albedo.glsl.h"
#endif

vec3 levelRadiance(int probe, vec3 p, vec3 lhat, inout int fetches) {
    gProbe = probe;
    DistanceParams q = uLevel.probes[probe].lookup;
#if HAS_GLOSSY
    GlossySample g = probeGlossySample(p - q.centre, lhat, gRoughness, q, uChainLevels);
    fetches += g.fetches;
    return g.radiance;
#else
    return probeRadiance(p - q.centre, lhat, q, fetches);
#endif
}

SeenSample levelSeen(int probe, vec3 p, vec3 lhat) {
    gProbe = probe;
    DistanceParams q = uLevel.probes[probe].lookup;
#if HAS_GLOSSY
    return probeGlossySeen(p - q.centre, lhat, gRoughness, q, uChainLevels);
#else
    return probeSampleSeen(p - q.centre, lhat, q);
#endif
}

#include "components/reflection_probe/distance/shaders/distance_level_blend.glsl.h"

vec3 speculaReflect(vec3 worldPos, vec3 normal, vec3 viewDir, float roughness) {
    vec3 v = normalize(viewDir);
    vec3 geometric = normalize(cross(dFdx(worldPos), dFdy(worldPos)));
    vec3 n = safeNormal(normal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));
#if HAS_GLOSSY
    gRoughness = max(roughness, 0.0);
#endif
    vec3 colour = blendLevel(worldPos, lhat, LEVEL_BLEND, LEVEL_K).radiance;
#if HAS_GLOSSY
    colour *= ggxAlbedo(abs(dot(n, v)), gRoughness);
#endif
    return colour;
}
