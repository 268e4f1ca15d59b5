// Reflector pixels of a distance-cubemap probe. Permutation defines (0 or 1): HAS_ENVMAP,
// HAS_BOXPROJ, HAS_BISECTION, HAS_SECANT, HAS_AVGDIST, HAS_LAYERS, HAS_FRESNEL, and
// OUTPUT (0 colour, 1 probe-local position, 2 reflected direction: inputs for the CPU twin).
#include "engine/core/glsl_device.glsl"
#include "engine/math/cube_face.glsl.h"
#include "engine/scene/shading.glsl.h"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"

// Faces of layer L are array layers 6L .. 6L+5; RGB radiance, A distance.
uniform sampler2DArray uLayers;
uniform sampler2D uSky;
uniform int uHasSky;
uniform int uFaceRes;
uniform vec3 uProbeCentre;
uniform vec3 uEye;
uniform vec3 uBoxMin;
uniform vec3 uBoxMax;
uniform float uRange;
uniform float uTolerance;
uniform float uDInf;
uniform int uMaxSteps;
uniform int uMethod;
uniform int uLayerCount;
uniform int uLayerMethod[64];
uniform float uLayerAvgDistance[64];
uniform vec3 uLayerBoxMin[64];
uniform vec3 uLayerBoxMax[64];
uniform float uF0;

in vec3 vWorldPos;
in vec3 vNormal;
out vec4 fragColor;

float fetchDistance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    ivec2 texel = min(ivec2(f.xy * float(uFaceRes)), ivec2(uFaceRes - 1));
    return texelFetch(uLayers, ivec3(texel, layer * 6 + int(f.z)), 0).a;
}

vec3 fetchRadiance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    return textureLod(uLayers, vec3(f.xy, float(layer * 6) + f.z), 0.0).rgb;
}

vec3 fetchSky(vec3 dir) {
    return uHasSky != 0 ? textureLod(uSky, equirectUv(dir), 0.0).rgb : vec3(0.0);
}

int layerMethod(int layer) { return uLayerMethod[layer]; }
float layerAvgDistance(int layer) { return uLayerAvgDistance[layer]; }
vec3 layerBoxMin(int layer) { return uLayerBoxMin[layer]; }
vec3 layerBoxMax(int layer) { return uLayerBoxMax[layer]; }

#include "components/reflection_probe/shaders/distance_lookup.glsl.h"

void main() {
    // Probe-local space: the lookup never sees world coordinates.
    vec3 x = vWorldPos - uProbeCentre;
    vec3 v = normalize(vWorldPos - uEye);
    vec3 geometric = normalize(cross(dFdx(vWorldPos), dFdy(vWorldPos)));
    vec3 n = safeNormal(vNormal, geometric);
    vec3 lhat = normalize(mirrorDirection(v, n));

    ProbeLookupParams p;
    p.boxMin = uBoxMin;
    p.boxMax = uBoxMax;
    p.range = uRange;
    p.tolerance = uTolerance;
    p.dInf = uDInf;
    p.maxSteps = uMaxSteps;
    p.method = uMethod;
    p.layerCount = uLayerCount;
    int fetches = 0;
    vec3 colour = probeRadiance(x, lhat, p, fetches);
#if HAS_FRESNEL
    colour *= schlickFresnel(uF0, abs(dot(n, v)));
#endif
#if OUTPUT == 1
    fragColor = vec4(x, 1.0);
#elif OUTPUT == 2
    fragColor = vec4(lhat, 1.0);
#else
    fragColor = vec4(colour, 1.0);
#endif
}
