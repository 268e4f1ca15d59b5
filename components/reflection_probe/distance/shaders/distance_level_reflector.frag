// Reflector pixels of a level of distance probes: up to LEVEL_K probes blended per pixel
// (distance_level_blend.glsl.h). Permutation defines (0 or 1): HAS_ENVMAP, HAS_BOXPROJ,
// HAS_BISECTION, HAS_SECANT (the one method every probe runs; HAS_AVGDIST and HAS_LAYERS
// are 0: each probe looks up its composite), HAS_GLOSSY, HAS_ROUGHNESS_MAP, HAS_FRESNEL;
// LEVEL_K (probes per pixel), LEVEL_BLEND (kLevelBlend*), and OUTPUT (0 colour, 1 world
// position, 2 reflected direction, 3 |n.v| in red, 4 TEXCOORD_0 in red and green: the CPU
// twin's inputs). HAS_GLOSSY (a rough reflector, issue 14) blends each probe's glossy sample
// (its chain read at its own hit, the footprint level there: distance_glossy_seen.glsl.h)
// with the mirror's weights, times the GGX directional albedo E(|n.v|, roughness), as the
// single probe's shader does, at the pixel's roughness (reflector_roughness.glsl.h: times the
// roughness map with HAS_ROUGHNESS_MAP); without it not one line of the glossy path is
// compiled.
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/math/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_level_gpu.glsl"

uniform sampler2D uSky;
uniform int uHasSky;
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
in vec2 vUv;
out vec4 fragColor;

vec3 fetchSky(vec3 dir) {
    return uHasSky != 0 ? textureLod(uSky, equirectUv(dir), 0.0).rgb : vec3(0.0);
}

#include "components/reflection_probe/distance/shaders/distance_lookup.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_seen.glsl.h"

#if HAS_GLOSSY
uniform float uRoughness; // perceptual factor, > 0 (alpha = roughness^2)
uniform int uChainLevels; // every probe's chain's levels, the composite (level 0) included
#include "components/reflection_probe/shaders/reflector_roughness.glsl.h"
// This pixel's roughness (set by main before the blend): every probe's lookup reads it.
float gRoughness;
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

void main() {
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));

#if HAS_GLOSSY
    gRoughness = reflectorRoughness(uRoughness, vUv);
#endif
    LevelBlendSample s = blendLevel(vWorldPos, lhat, LEVEL_BLEND, LEVEL_K);
    vec3 colour = s.radiance;
#if HAS_GLOSSY
    colour *= ggxAlbedo(abs(dot(n, v)), gRoughness);
#endif
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(vWorldPos, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#elif OUTPUT == 3
    fragColor = vec4(abs(dot(n, v)), 0.0, 0.0, 1.0);
#elif OUTPUT == 4
    fragColor = vec4(vUv, 0.0, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
