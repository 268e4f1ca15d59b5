// Reflector pixels of the constant-colour test flavour. Defines: HAS_FRESNEL (0/1), OUTPUT
// (0 colour; 1 and 2 write the position / direction like every flavour's twin outputs; 3
// and 4 the reflected direction's dFdxFine / dFdyFine).
#include "engine/core/glsl_device.glsl"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"
#include "tests/probe/constant_flavour/constant_params.glsl.h"

layout(std140, binding = kConstantParamsBinding) uniform ConstantParamsUniforms {
    ConstantParams uConstant;
};
uniform vec3 uEye;
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
out vec4 fragColor;

void main() {
    vec3 colour = constantRadiance(uConstant);
#if HAS_FRESNEL
    vec3 v = normalize(vWorldPos - uEye);
    colour *= schlickFresnel(uF0, abs(dot(normalize(vNormal), v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(vWorldPos, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(normalize(vNormal), 1.0);
#elif OUTPUT == 3 || OUTPUT == 4
    // The fine screen derivatives of the reflected direction, computed as every flavour
    // computes the direction: what ReflectorQuadPixel's twin must reproduce.
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 lhat = normalize(mirrorDirection(v, safeNormal(vNormal, geometric)));
#if OUTPUT == 3
    fragColor = vec4(dFdxFine(lhat), 1.0);
#else
    fragColor = vec4(dFdyFine(lhat), 1.0);
#endif
#else
    fragColor = vec4(colour, 1.0);
#endif
}
