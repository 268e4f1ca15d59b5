// The GPU side of a level of distance probes: every probe's composite in one texture array
// (probe i's faces are layers 6i .. 6i+5), the level's parameter block
// (distance_level_params.glsl.h) and the draw's candidates, with the fetches
// distance_lookup.glsl.h expects and the hooks of distance_level_blend.glsl.h. The lookup
// functions read the probe `gProbe` names, set before each probe's lookup. The includer adds
// fetchSky().
#ifndef SPECULA_DISTANCE_LEVEL_GPU_GLSL
#define SPECULA_DISTANCE_LEVEL_GPU_GLSL

#include "components/reflection_probe/shaders/probe_influence.glsl.h"
#include "components/reflection_probe/distance/shaders/distance_level_params.glsl.h"

// COMPRESSED_COMPOSITE = 1 (every probe cooked with --compress bc6h): uLevelLayers holds the
// radiance as BC6H blocks, uLevelDistances (R16F or R32F) the distances of the same texels.
#ifndef COMPRESSED_COMPOSITE
#define COMPRESSED_COMPOSITE 0
#endif

uniform sampler2DArray uLevelLayers;
#if COMPRESSED_COMPOSITE
uniform sampler2DArray uLevelDistances;
#endif
layout(std140, binding = kLevelParamsBinding) uniform LevelParamsUniforms {
    LevelParamsBlock uLevel;
};
uniform int uProbeCount;                  // probes in the level
uniform int uCandidateCount;              // probes whose influence meets this reflector
uniform int uCandidates[kMaxLevelProbes]; // (their indices, ascending: blend order)

int gProbe = 0;

int probeLayer(vec3 f) { return gProbe * 6 + int(f.z); }

float fetchDistance(int layer, vec3 dir) {
    int faceRes = uLevel.probes[gProbe].lookup.faceRes;
    vec3 f = cubeFaceUv(dir);
    ivec2 texel = min(ivec2(f.xy * float(faceRes)), ivec2(faceRes - 1));
#if COMPRESSED_COMPOSITE
    return texelFetch(uLevelDistances, ivec3(texel, probeLayer(f)), 0).r;
#else
    return texelFetch(uLevelLayers, ivec3(texel, probeLayer(f)), 0).a;
#endif
}

vec4 fetchDistanceGather(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
#if COMPRESSED_COMPOSITE
    return textureGather(uLevelDistances, vec3(f.xy, float(probeLayer(f))), 0);
#else
    return textureGather(uLevelLayers, vec3(f.xy, float(probeLayer(f))), 3);
#endif
}

vec3 fetchRadiance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
    return textureLod(uLevelLayers, vec3(f.xy, float(probeLayer(f))), 0.0).rgb;
}

// Only the composite is uploaded: the layered lookup is not compiled in (HAS_LAYERS 0).
int layerMethod(int layer) { return uLevel.probes[gProbe].lookup.method; }
float layerAvgDistance(int layer) { return uLevel.probes[gProbe].composite.avgDistance; }
vec3 layerBoxMin(int layer) { return uLevel.probes[gProbe].composite.boxMin; }
vec3 layerBoxMax(int layer) { return uLevel.probes[gProbe].composite.boxMax; }
float layerReach(int layer) { return uLevel.probes[gProbe].composite.reach; }

int levelCandidateCount() { return uCandidateCount; }
int levelCandidate(int i) { return uCandidates[i]; }

float levelInfluence(int probe, vec3 p) {
    LevelProbeParams q = uLevel.probes[probe];
    float depth = influenceDepthOf(q.influenceShape, q.influenceMin, q.influenceMax,
                                   q.influenceCentre, q.influenceRadius, p);
    return influenceWeightOf(depth, q.blendDistance);
}

// Ties go to the probe first in blend order.
int levelNearest(vec3 p) {
    int best = 0;
    float bestDistance = 1e30;
    for (int i = 0; i < uProbeCount; ++i) {
        float d = distance(p, uLevel.probes[i].lookup.centre);
        if (d < bestDistance) {
            best = i;
            bestDistance = d;
        }
    }
    return best;
}

#endif
