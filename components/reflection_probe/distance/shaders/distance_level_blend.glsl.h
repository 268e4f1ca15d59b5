// Shared by GLSL and C++ (see engine/core/glsl_host.h): one reflector point of a level looked
// up through up to K of its distance probes (issue 13), three ways:
//   nearest     the probe nearest to the point alone;
//   engine      what engines do: probes in blend order (priority, then the smaller volume),
//               each taking its influence of what the ones before left, the rest the sky's;
//   visibility  the engine's order and influences, each probe further weighed by how surely
//               it sees what its lookup proposes (SeenSample.visibility), so a probe behind a
//               wall adds nothing and leaves its share to the probes that see the hit.
// The includer provides, besides fetchSky(dir):
//   int   levelCandidateCount()                 probes that may have influence here,
//   int   levelCandidate(int i)                 in blend order (i < count)
//   float levelInfluence(int probe, vec3 p)     0 outside its influence volume .. 1
//   int   levelNearest(vec3 p)                  the probe nearest to p (of the whole level)
//   vec3  levelRadiance(int probe, vec3 p, vec3 lhat, INOUT(int) fetches)   its plain lookup
//   SeenSample levelSeen(int probe, vec3 p, vec3 lhat)   its lookup with its verdict
// All points are in world space; the hooks make them probe-local. For a rough reflector
// (issue 14) the two lookup hooks return each probe's glossy sample with the mirror ray's
// verdict (distance_glossy_seen.glsl.h): the weights here are the mirror's either way.
#ifndef SPECULA_DISTANCE_LEVEL_BLEND_GLSL_H
#define SPECULA_DISTANCE_LEVEL_BLEND_GLSL_H

#include "components/reflection_probe/distance/shaders/distance_level_params.glsl.h"

struct LevelBlendSample {
    vec3 radiance;
    int count; // entries of probe[] and weight[]
    int probe[kMaxLevelK];
    float weight[kMaxLevelK]; // radiance = sum weight[i] probe[i] + sky x the sky
    float sky;
    int fetches;
    int hidden; // visibility: probes with influence here that did not see the hit
    // Visibility: the seen probes' influence x visibility, summed (at most 1); below 1 the
    // answer is that share of the seen probes' blend and the rest the engine's.
    float confidence;
    bool fallback; // no probe with influence saw the hit (the engine's blend), or none has
                   // influence (the nearest probe)
    bool outside;  // no probe has influence here: the nearest answered
};

LevelBlendSample emptyLevelSample() {
    LevelBlendSample s;
    s.radiance = vec3(0.0f);
    s.count = 0;
    for (int i = 0; i < kMaxLevelK; ++i) {
        s.probe[i] = -1;
        s.weight[i] = 0.0f;
    }
    s.sky = 0.0f;
    s.fetches = 0;
    s.hidden = 0;
    s.confidence = 0.0f;
    s.fallback = false;
    s.outside = false;
    return s;
}

// The nearest probe alone.
LevelBlendSample nearestLevelSample(vec3 p, vec3 lhat) {
    LevelBlendSample s = emptyLevelSample();
    int probe = levelNearest(p);
    s.radiance = levelRadiance(probe, p, lhat, s.fetches);
    s.count = 1;
    s.probe[0] = probe;
    s.weight[0] = 1.0f;
    return s;
}

LevelBlendSample blendLevel(vec3 p, vec3 lhat, int blend, int k) {
    if (blend == kLevelBlendNearest) return nearestLevelSample(p, lhat);
    LevelBlendSample s = emptyLevelSample();
    // One walk over the first k probes with influence here computes both blends: the
    // engine's weights (influence x what the probes before left) and the visibility
    // weights (the same, times each probe's visibility), on the same lookups.
    vec3 engine = vec3(0.0f);
    vec3 seen = vec3(0.0f);
    float engineLeft = 1.0f;
    float seenLeft = 1.0f;
    float engineWeight[kMaxLevelK];
    float seenWeight[kMaxLevelK];
    int used = 0;
    for (int c = 0; c < levelCandidateCount() && used < k; ++c) {
        int probe = levelCandidate(c);
        float influence = levelInfluence(probe, p);
        if (influence <= 0.0f) continue;
        // The engine blend stops once the probes before took everything.
        if (blend == kLevelBlendEngine && engineLeft <= 0.0f) break;
        SeenSample q;
        if (blend == kLevelBlendEngine) {
            int fetches = 0;
            q.radiance = levelRadiance(probe, p, lhat, fetches);
            q.visibility = 1.0f;
            q.seen = true;
            q.fetches = fetches;
            q.t = 0.0f;
        } else {
            q = levelSeen(probe, p, lhat);
        }
        s.fetches += q.fetches;
        s.hidden += q.seen ? 0 : 1;
        s.probe[used] = probe;
        engineWeight[used] = influence * max(engineLeft, 0.0f);
        engine += engineWeight[used] * q.radiance;
        engineLeft -= engineWeight[used];
        s.confidence = min(1.0f, s.confidence + influence * q.visibility);
        seenWeight[used] = influence * q.visibility * seenLeft;
        seen += seenWeight[used] * q.radiance;
        seenLeft -= seenWeight[used];
        used += 1;
    }
    if (used == 0) {
        // Outside every influence volume: the nearest probe answers, flagged.
        LevelBlendSample n = nearestLevelSample(p, lhat);
        n.fallback = true;
        n.outside = true;
        return n;
    }
    s.count = used;
    s.sky = max(engineLeft, 0.0f);
    vec3 skyRadiance = vec3(0.0f);
    if (s.sky > 0.0f) {
        skyRadiance = fetchSky(lhat);
        s.fetches += 1;
    }
    // The engine's blend; also the visibility blend's answer when no probe saw the hit.
    bool engineOnly = blend == kLevelBlendEngine || seenLeft >= 1.0f;
    s.fallback = blend == kLevelBlendVisibility && seenLeft >= 1.0f;
    float fromSeen = engineOnly ? 0.0f : s.confidence;
    // What the seen probes leave goes to them in proportion (not to the sky: a hidden
    // probe's share is a wall's, not the sky's), then the engine's own sky share; below full
    // confidence the rest is the engine's blend, so a probe entering over its blend distance,
    // or a verdict near the edge of its band, changes the pixel gradually.
    float scale = engineOnly ? 0.0f : (1.0f - s.sky) / (1.0f - seenLeft);
    s.radiance = fromSeen * scale * seen + (1.0f - fromSeen) * engine + s.sky * skyRadiance;
    for (int i = 0; i < used; ++i)
        s.weight[i] = fromSeen * scale * seenWeight[i] + (1.0f - fromSeen) * engineWeight[i];
    return s;
}

#endif
