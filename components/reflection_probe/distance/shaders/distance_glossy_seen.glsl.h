// Shared by GLSL and C++ (see engine/core/glsl_host.h): a probe's glossy lookup with its
// visibility verdict, what a level blends for a rough reflector (distance_level_blend.glsl.h,
// issue 14). The verdict is the mirror ray's (distance_seen.glsl.h): whether the probe sees
// the hit its search proposes; the radiance is the composite's prefiltered chain read there
// (distance_glossy_lookup.glsl.h: the footprint level at this probe's own hit), so the
// level's weights are the mirror level's and each probe's share is its own glossy sample.
// One search serves both. Included after distance_seen.glsl.h and
// distance_glossy_lookup.glsl.h, with HAS_LAYERS 0 (the composite decides, as in
// probeSampleSeen).
#ifndef SPECULA_DISTANCE_GLOSSY_SEEN_GLSL_H
#define SPECULA_DISTANCE_GLOSSY_SEEN_GLSL_H

// probeSampleSeen with the radiance of glossyAtHit; roughness <= 0 (or NaN) is exactly
// probeSampleSeen.
SeenSample probeGlossySeen(vec3 x, vec3 lhat, float roughness, DistanceParams p, int levels) {
    LayerHit h = seenLookup(x, lhat, p);
    SeenSample s = seenAtHit(x, lhat, p, h);
    if (!(roughness > 0.0f)) return s;
    GlossySample g = glossyAtHit(x, lhat, roughness, p.method, levels, h);
    s.radiance = g.radiance;
    // The chain read replaces the hit's radiance fetch, or the sky's where nothing was hit
    // (glossyAtHit counts the search's fetches and the chain's, less the one it replaces).
    s.fetches += g.fetches - h.fetches - (h.hit ? 0 : 1);
    return s;
}

#endif
