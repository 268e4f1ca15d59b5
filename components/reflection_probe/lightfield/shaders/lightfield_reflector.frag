// Reflector pixels of a light-field-slab probe: speculaReflect of the host library
// (lightfield_host.glsl, what a host's shader calls), times Fresnel; with BACKGROUND=1 the
// environment seen from an eye inside the slabs. Permutation defines: HAS_FRESNEL (0/1),
// BACKGROUND (0/1), GLOSSY (0/1: a rough reflector, the slabs' GGX filter over the atlas's
// mips, times the GGX albedo E), HAS_ROUGHNESS_MAP (0/1: with GLOSSY, the roughness is
// uRoughness times the roughness map at the pixel's TEXCOORD_0, reflector_roughness.glsl.h),
// OUTPUT (0 colour, 1 cell-local position, 2 lookup direction, 3 shading normal, 4 TEXCOORD_0
// in red and green: inputs for the CPU twin).
#include "components/reflection_probe/lightfield/shaders/lightfield_host.glsl"

uniform vec3 uEye;
uniform float uF0;
#if BACKGROUND
uniform mat4 uInvViewProj;
uniform vec2 uViewport;
#else
in vec3 vWorldPos;
in vec3 vNormal;
in vec2 vUv;
#endif
out vec4 fragColor;

#if GLOSSY
uniform float uRoughness; // perceptual factor, > 0
#include "components/reflection_probe/shaders/reflector_roughness.glsl.h"
#endif

void main() {
#if BACKGROUND
    // The eye ray through this pixel, from the eye: the light field is the environment as
    // seen from anywhere in the cell.
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec4 farP = uInvViewProj * vec4(ndc, 1.0, 1.0);
    vec3 x = uEye - uCellCentre;
    vec3 lhat = normalize(farP.xyz / farP.w - uEye);
    vec3 colour = lightFieldRadiance(x, lhat, lightFieldParams());
#else
    vec3 v = normalize(vWorldPos - uEye);
#if GLOSSY
    vec3 colour = speculaReflect(vWorldPos, vNormal, v, reflectorRoughness(uRoughness, vUv));
#else
    vec3 colour = speculaReflect(vWorldPos, vNormal, v, 0.0);
#endif
    // The twin's inputs, as speculaReflect derives them.
    vec3 x = vWorldPos - uCellCentre;
    vec3 n = safeNormal(vNormal, normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos))));
    vec3 lhat = normalize(mirrorDirection(v, n));
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#elif OUTPUT == 3 && !BACKGROUND
    fragColor = vec4(n, 1.0);
#elif OUTPUT == 4 && !BACKGROUND
    fragColor = vec4(vUv, 0.0, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
