// Shared by GLSL and C++ (see engine/core/glsl_host.h): a distance probe's glossy reflection
// (issue 14), the shader's HAS_GLOSSY path and the CPU twin's glossySample. The mirror search
// finds the hit, and the composite's GGX prefiltered chain (engine/image/ggx_prefilter.h) is
// read there instead of the composite itself.
//
// Included after distance_lookup.glsl.h (probeHit, fetchSky) and
// engine/math/cube_chain_sample.glsl.h (sampleCubeChain) over the chain of the composite:
// level 0 is the composite (layer 0) itself, levels 1 .. levels - 1 its prefiltered levels.
//
// Where the chain is read, and at which level:
//   envmap        the direction lhat, level by roughness alone as engines map it
//                 (glossyEngineLevel: these two methods stand for what engines do);
//   boxproj       the box-projected point x + t lhat (t: the box exit), the same level;
//   bisection, secant, avgdist, and the nearest hit of layered mode
//                 the hit the search found, read where the mirror reads it (LayerHit::at:
//                 the search's last point), level from the lobe's footprint at its ray
//                 distance t (distance_glossy.glsl.h: sharper near contact);
//   no hit        (the search ended on d_inf) the direction lhat, level by roughness: the
//                 composite holds the sky where it sees nothing, so its chain has the sky's
//                 blur there.
// Below level 1, level 0 is the mirror lookup's own answer (glossyMirrorShare): the sky
// panorama where nothing was hit, the object layer's texel in layered mode, the composite's
// texel otherwise (which is the chain's level 0 there).
// Layered mode searches the object layers for the nearest hit, then reads the composite's
// chain at it: the composite holds, in the direction of q, the nearest surface from the
// centre, which is the hit unless something nearer the centre hides it.
#ifndef SPECULA_DISTANCE_GLOSSY_LOOKUP_GLSL_H
#define SPECULA_DISTANCE_GLOSSY_LOOKUP_GLSL_H

#include "components/reflection_probe/distance/shaders/distance_glossy.glsl.h"

// Texels a chain read fetches: four in each of the two levels it blends.
SHARED_CONST int kGlossyChainFetches = 8;

// The prefiltered radiance of a GGX lobe about the unit mirror direction lhat leaving the
// probe-local point x, for perceptual roughness `roughness` (alpha = roughness^2, clamped to
// [0, 1]), over a chain of `levels` levels, where the mirror search of x along lhat by
// `method` found h (probeHit; layered mode passes a searching method: its nearest hit is a
// search's). Roughness <= 0 (or NaN) is the mirror lookup, exactly probeRadiance: no chain
// read. Apart from probeGlossySample so that a level (distance_glossy_seen.glsl.h) reads the
// chain at the hit its visibility verdict was taken on, with no second search.
GlossySample glossyAtHit(vec3 x, vec3 lhat, float roughness, int method, int levels,
                         LayerHit h) {
    GlossySample s;
    s.radiance = h.radiance;
    s.level = 0.0f;
    s.t = h.t;
    s.hit = h.hit;
    s.fetches = h.fetches;
    if (!(roughness > 0.0f)) {
        if (!h.hit) {
            s.radiance = fetchSky(lhat);
            s.fetches += 1;
        }
        return s;
    }
    // envmap and boxproj stand for engines: their level; a search's hit: the footprint
    // level there; no hit: the level of the roughness alone.
    int n = chainFaceRes(0);
    if (method == kMethodEnvmap || method == kMethodBoxProj)
        s.level = glossyEngineLevel(roughness, levels);
    else if (h.hit)
        s.level = glossyFootprintLevel(roughness, x, lhat, h.t, levels, n);
    else
        s.level = glossyRoughnessLevel(roughness, levels, n);
    vec3 at = h.hit ? h.at : lhat;
    float share = glossyMirrorShare(s.level);
    if (!(share > 0.0f)) {
        s.radiance = sampleCubeChain(at, s.level, levels);
        // The hit's own radiance fetch is not spent: the chain read replaces it.
        s.fetches += kGlossyChainFetches - (h.hit ? 1 : 0);
        return s;
    }
    // Below level 1: the mirror's own answer blended with level 1 (glossyMirrorShare).
    vec3 mirror = h.radiance;
    if (!h.hit) {
        mirror = fetchSky(lhat);
        s.fetches += 1;
    }
    s.radiance = mix(sampleCubeChain(at, 1.0f, levels), mirror, share);
    s.fetches += kGlossyChainFetches / 2;
    return s;
}

// glossyAtHit at the probe's own mirror search.
GlossySample probeGlossySample(vec3 x, vec3 lhat, float roughness, DistanceParams p,
                               int levels) {
#if HAS_LAYERS
    int method = kMethodSecant; // the nearest object layer's hit: the footprint level there
#else
    int method = p.method;
#endif
    return glossyAtHit(x, lhat, roughness, method, levels, probeHit(x, lhat, p));
}

#endif
