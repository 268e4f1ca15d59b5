// The GPU side of a distance probe's data, shared by every shader that runs the lookup
// (the reflector pass and the numerics harness): the uniforms setDistanceLookupUniforms()
// fills and the fetches distance_lookup.glsl.h expects. The includer adds fetchSky().
#ifndef SPECULA_DISTANCE_PROBE_GPU_GLSL
#define SPECULA_DISTANCE_PROBE_GPU_GLSL

// Faces of layer L are array layers 6L .. 6L+5; RGB radiance, A distance.
uniform sampler2DArray uLayers;
uniform int uFaceRes;
uniform vec3 uProbeCentre;
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
uniform float uLayerReach[64];

float fetchDistance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    ivec2 texel = min(ivec2(f.xy * float(uFaceRes)), ivec2(uFaceRes - 1));
    return texelFetch(uLayers, ivec3(texel, layer * 6 + int(f.z)), 0).a;
}

vec3 fetchRadiance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    return textureLod(uLayers, vec3(f.xy, float(layer * 6) + f.z), 0.0).rgb;
}

int layerMethod(int layer) { return uLayerMethod[layer]; }
float layerAvgDistance(int layer) { return uLayerAvgDistance[layer]; }
vec3 layerBoxMin(int layer) { return uLayerBoxMin[layer]; }
vec3 layerBoxMax(int layer) { return uLayerBoxMax[layer]; }
float layerReach(int layer) { return uLayerReach[layer]; }

ProbeLookupParams lookupParams() {
    ProbeLookupParams p;
    p.boxMin = uBoxMin;
    p.boxMax = uBoxMax;
    p.range = uRange;
    p.tolerance = uTolerance;
    p.dInf = uDInf;
    p.maxSteps = uMaxSteps;
    p.method = uMethod;
    p.layerCount = uLayerCount;
    return p;
}

#endif
