// Shared by GLSL and C++ (see engine/core/glsl_host.h): whether a distance probe actually
// sees what its lookup proposes, for blending several probes by visibility (issue 13). A
// probe in the next room proposes a hit on the far side of the wall between them; its
// stored distances know the wall is there. Included after distance_lookup.glsl.h (uses
// lookupLayer, makeSpan, fetchSky and fetchDistanceGather(layer, dir): the four stored
// distances a bilinear fetch at dir would weigh, as textureGather returns them), with
// HAS_LAYERS 0: the composite decides.
#ifndef SPECULA_DISTANCE_SEEN_GLSL_H
#define SPECULA_DISTANCE_SEEN_GLSL_H

// Stored distances are the nearest texel's: across a texel, a surface seen at a grazing
// angle changes its distance by a lot (a floor 8 m away seen 8 degrees down: 9% a texel at
// 128^2). A point is judged against the 2 x 2 texels around its direction (one gather on the
// GPU), which span that change, with a small relative slack for what lies between texel
// centres.
SHARED_CONST float kSeenRelativeSlack = 0.04f;

float seenBand(vec3 q, DistanceParams p) {
    return kSeenRelativeSlack * length(q) + p.tolerance;
}

// 1 while q (probe-local) is not behind the farthest of the texels around its direction by
// more than the band, 0 beyond twice the band.
float pointVisibility(vec3 q, DistanceParams p) {
    vec4 d = fetchDistanceGather(0, q);
    float far = max(max(d.x, d.y), max(d.z, d.w));
    float band = seenBand(q, p);
    return clamp(2.0f - (length(q) - far) / band, 0.0f, 1.0f);
}

// 1 while q lies on the probe's stored surface (the nearest of the texels around its
// direction within the band), 0 beyond twice the band.
float surfaceAgreement(vec3 q, DistanceParams p) {
    vec4 e = abs(fetchDistanceGather(0, q) - vec4(length(q)));
    float band = seenBand(q, p);
    return clamp(2.0f - min(min(e.x, e.y), min(e.z, e.w)) / band, 0.0f, 1.0f);
}

// The composite's lookup of the ray x + t lhat (probe-local) that seenAtHit judges.
LayerHit seenLookup(vec3 x, vec3 lhat, DistanceParams p) {
    return lookupLayer(p.method, 0, x, lhat, p, makeSpan(0.0f, 2.0f * p.range, p.maxSteps));
}

// The verdict on h, the composite's lookup of the ray x + t lhat (probe-local, seenLookup):
// the reflector point's visibility, times, for a rectifying method, the agreement of the
// stored distance at the hit the search ended on with the hit's own distance (a search that
// found no crossing ends where they disagree).
SeenSample seenAtHit(vec3 x, vec3 lhat, DistanceParams p, LayerHit h) {
    SeenSample s;
    s.visibility = pointVisibility(x, p);
    s.fetches = 1 + h.fetches;
    s.t = h.t;
    if (!h.hit) {
        s.radiance = fetchSky(lhat);
        s.fetches += 1;
    } else {
        s.radiance = h.radiance;
        if (p.method == kMethodBisection || p.method == kMethodSecant ||
            p.method == kMethodMarch) {
            s.visibility *= surfaceAgreement(x + h.t * lhat, p);
            s.fetches += 1;
        }
    }
    s.seen = s.visibility >= 0.5f;
    return s;
}

// The probe's composite lookup of the ray x + t lhat (probe-local) with its verdict.
SeenSample probeSampleSeen(vec3 x, vec3 lhat, DistanceParams p) {
    return seenAtHit(x, lhat, p, seenLookup(x, lhat, p));
}

#endif
