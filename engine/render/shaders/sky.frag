// Distant environment looked up by direction alone, through each pixel's centre.
#include "engine/math/shading.glsl.h"

uniform mat4 uInvViewProjRot; // inverse(proj * mat4(mat3(view))): eye-relative directions
uniform vec4 uViewport;       // x, y, width, height, as glViewport
uniform sampler2D uSky;

layout(location = 0) out vec4 fragColor;

void main() {
    // gl_FragCoord is at the pixel centre, as CameraView::primaryRay samples it.
    vec2 ndc = (gl_FragCoord.xy - uViewport.xy) / uViewport.zw * 2.0 - 1.0;
    vec4 nearP = uInvViewProjRot * vec4(ndc, -1.0, 1.0);
    vec4 farP = uInvViewProjRot * vec4(ndc, 1.0, 1.0);
    vec3 dir = normalize(farP.xyz / farP.w - nearP.xyz / nearP.w);
    fragColor = vec4(texture(uSky, equirectUv(dir)).rgb, 1.0);
}
