// House shading, the same function the bake and the ray tracer call on the CPU.
#include "engine/math/shading.glsl.h"

in vec3 vNormal;
in vec2 vUv;

uniform vec4 uBaseColorFactor;
uniform sampler2D uBaseColorTexture;

layout(location = 0) out vec4 fragColor;

void main() {
    vec3 albedo = uBaseColorFactor.rgb * texture(uBaseColorTexture, vUv).rgb;
    // Interpolation shortens the normal; the CPU twin shades a unit normal.
    fragColor = vec4(shadeSurface(albedo, normalize(vNormal)), 1.0);
}
