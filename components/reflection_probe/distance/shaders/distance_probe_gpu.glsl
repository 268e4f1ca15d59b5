// The GPU side of a distance probe's data, shared by every shader that runs the lookup
// (the reflector pass and the numerics harness): the parameter block of
// distance_params.glsl.h, uploaded as one uniform buffer, and the fetches
// distance_lookup.glsl.h expects. The includer adds fetchSky().
#ifndef SPECULA_DISTANCE_PROBE_GPU_GLSL
#define SPECULA_DISTANCE_PROBE_GPU_GLSL

// Faces of layer L are array layers 6L .. 6L+5; RGB radiance, A distance.
uniform sampler2DArray uLayers;

layout(std140, binding = kDistanceParamsBinding) uniform DistanceParamsUniforms {
    DistanceParamsBlock uDistance;
};

float fetchDistance(int layer, vec3 dir) {
    int faceRes = uDistance.params.faceRes;
    vec3 f = cubeFaceUv(dir);
    ivec2 texel = min(ivec2(f.xy * float(faceRes)), ivec2(faceRes - 1));
    return texelFetch(uLayers, ivec3(texel, layer * 6 + int(f.z)), 0).a;
}

// The 2 x 2 stored distances a bilinear fetch at dir weighs (distance_seen.glsl.h).
vec4 fetchDistanceGather(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    return textureGather(uLayers, vec3(f.xy, float(layer * 6) + f.z), 3);
}

vec3 fetchRadiance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    return textureLod(uLayers, vec3(f.xy, float(layer * 6) + f.z), 0.0).rgb;
}

int layerMethod(int layer) { return uDistance.layers[layer].method; }
float layerAvgDistance(int layer) { return uDistance.layers[layer].avgDistance; }
vec3 layerBoxMin(int layer) { return uDistance.layers[layer].boxMin; }
vec3 layerBoxMax(int layer) { return uDistance.layers[layer].boxMax; }
float layerReach(int layer) { return uDistance.layers[layer].reach; }

DistanceParams lookupParams() { return uDistance.params; }

vec3 probeCentre() { return uDistance.params.centre; }

#endif
