// Reflector pixels of a level of distance probes: speculaReflect of the host library
// (distance_level_host.glsl, what a host's shader calls), up to LEVEL_K probes blended per
// pixel (distance_level_blend.glsl.h), times Fresnel. Permutation defines (0 or 1): HAS_ENVMAP, HAS_BOXPROJ,
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
#include "components/reflection_probe/distance/shaders/distance_level_host.glsl"

uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
in vec2 vUv;
out vec4 fragColor;

#if HAS_GLOSSY
uniform float uRoughness; // perceptual factor, > 0 (alpha = roughness^2)
#include "components/reflection_probe/shaders/reflector_roughness.glsl.h"
#endif

void main() {
    vec3 v = normalize(vWorldPos - uEye);
#if HAS_GLOSSY
    vec3 colour = speculaReflect(vWorldPos, vNormal, v, reflectorRoughness(uRoughness, vUv));
#else
    vec3 colour = speculaReflect(vWorldPos, vNormal, v, 0.0);
#endif
    // The twin's inputs, as speculaReflect derives them.
    vec3 n = safeNormal(vNormal, normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos))));
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(vWorldPos, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(normalize(mirrorDirection(v, n)), 1.0);
#elif OUTPUT == 3
    fragColor = vec4(abs(dot(n, v)), 0.0, 0.0, 1.0);
#elif OUTPUT == 4
    fragColor = vec4(vUv, 0.0, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
