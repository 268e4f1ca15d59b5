// Reflector pixels of a distance-cubemap probe: speculaReflect of the host library
// (distance_host.glsl, what a host's shader calls) at the pixel's roughness, times Fresnel.
// Permutation defines (0 or 1): HAS_ENVMAP, HAS_BOXPROJ, HAS_BISECTION, HAS_SECANT,
// HAS_AVGDIST, HAS_LAYERS, HAS_GLOSSY, HAS_FRESNEL, HAS_ROUGHNESS_MAP, and OUTPUT (0 colour,
// 1 probe-local position, 2 reflected direction, 3 |n.v| in red, 4 TEXCOORD_0 in red and
// green: inputs for the CPU twin). HAS_GLOSSY (a rough reflector) reads the composite's
// prefiltered chain at the hit (distance_glossy_lookup.glsl.h) instead of the composite, times
// the GGX directional albedo E(|n.v|, roughness), at the pixel's roughness: uRoughness times the
// roughness map at the pixel's TEXCOORD_0 with HAS_ROUGHNESS_MAP (reflector_roughness.glsl.h),
// uRoughness alone without.
#include "components/reflection_probe/distance/shaders/distance_host.glsl"

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
    fragColor = vec4(vWorldPos - probeCentre(), 1.0);
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
