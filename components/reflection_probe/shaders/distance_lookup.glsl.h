// Shared by GLSL and C++ (see engine/core/glsl_host.h): the distance-cubemap lookups of
// Wang et al. 2012. The C++ copy is the CPU twin the tests hold the shader to.
//
// All positions are probe-local (origin at the probe centre). The includer provides:
//   float fetchDistance(int layer, vec3 dir)   nearest texel's distance (alpha); never
//                                             filtered: a blend of a distance and d_inf
//                                             across a silhouette means nothing
//   vec3  fetchRadiance(int layer, vec3 dir)   bilinear radiance (RGB)
//   vec3  fetchSky(vec3 dir)                   the distant environment
//   int   layerMethod(int layer)               method of each object layer (layered mode)
//   float layerAvgDistance(int layer)          d-bar of each layer
//   vec3  layerBoxMin(int layer), layerBoxMax(int layer)   probe-local bounds of a layer
// and defines HAS_ENVMAP, HAS_BOXPROJ, HAS_BISECTION, HAS_SECANT, HAS_AVGDIST, HAS_LAYERS
// as 0 or 1: a method the probe does not use is not compiled into its shader.
//
// Layer 0 is the composite (every environment object, sky in the texels that see none);
// layers 1..layerCount are single objects or groups, sorted near to far.
#ifndef SPECULA_DISTANCE_LOOKUP_GLSL_H
#define SPECULA_DISTANCE_LOOKUP_GLSL_H

#include "components/reflection_probe/shaders/distance_lookup_types.glsl.h"

bool isInfiniteDistance(float d, float dInf) { return d >= 0.5f * dInf; }

LayerHit makeHit(vec3 radiance, bool hit, int fetches) {
    LayerHit h;
    h.radiance = radiance;
    h.hit = hit;
    h.fetches = fetches;
    return h;
}

// Finishes a rectified lookup: the d_inf rule says a lookup that ends on a texel that sees
// nothing has no hit in this layer, which is what keeps silhouettes from smearing.
LayerHit finishRectified(int layer, vec3 l, float d, int fetches, float dInf) {
    if (isInfiniteDistance(d, dInf)) return makeHit(vec3(0.0f), false, fetches);
    return makeHit(fetchRadiance(layer, l), true, fetches + 1);
}

#if HAS_BOXPROJ
// Distance along l from x (inside the box) to the box wall it leaves through.
float boxExitDistance(vec3 x, vec3 l, vec3 boxMin, vec3 boxMax) {
    // Keep the sign of each component but never divide by less than 1e-8 in magnitude.
    vec3 s = vec3(l.x >= 0.0f ? 1.0f : -1.0f, l.y >= 0.0f ? 1.0f : -1.0f,
                  l.z >= 0.0f ? 1.0f : -1.0f);
    vec3 safeL = s * max(abs(l), vec3(1e-8f));
    vec3 t1 = (boxMax - x) / safeL;
    vec3 t2 = (boxMin - x) / safeL;
    vec3 tFar = max(t1, t2);
    return max(min(min(tFar.x, tFar.y), tFar.z), 0.0f);
}
#endif

#if HAS_BISECTION
// Bisection along x + t l, t in (0, 2D): start at t = D and move by D/2^n towards the
// surface until the stored distance agrees with |l| within d_e (condition 1) or N steps.
LayerHit lookupBisection(int layer, vec3 x, vec3 lhat, ProbeLookupParams p) {
    float step = p.range;
    vec3 l = x + p.range * lhat;
    float d = p.dInf;
    int fetches = 0;
    for (int n = 1; n <= p.maxSteps; ++n) {
        d = fetchDistance(layer, l);
        fetches += 1;
        float delta = d - length(l);
        if (abs(delta) < p.tolerance || n == p.maxSteps) break;
        step *= 0.5f;
        l += (delta > 0.0f ? step : -step) * lhat;
    }
    return finishRectified(layer, l, d, fetches, p.dInf);
}
#endif

#if HAS_SECANT
// Same bracket search as bisection (identical first steps), but once the surface is
// bracketed by a point before it (f > 0) and one beyond it (f < 0) the next t comes from
// the secant through both, with the Illinois weighting so one end cannot stall. A secant
// step that leaves the bracket, or an end that saw only d_inf, falls back to the midpoint.
LayerHit lookupSecant(int layer, vec3 x, vec3 lhat, ProbeLookupParams p) {
    float ta = 0.0f;
    float fa = 0.0f;
    bool haveA = false; // ta: last t before the surface with a finite stored distance
    float tb = 2.0f * p.range;
    float fb = 0.0f;
    bool haveB = false; // tb: last t beyond the surface
    int lastSide = 0;
    vec3 l = x + p.range * lhat;
    float d = p.dInf;
    int fetches = 0;
    for (int n = 1; n <= p.maxSteps; ++n) {
        float t = 0.5f * (ta + tb);
        if (haveA && haveB) {
            float candidate = ta + fa * (tb - ta) / (fa - fb);
            if (candidate > ta && candidate < tb) t = candidate;
        }
        l = x + t * lhat;
        d = fetchDistance(layer, l);
        fetches += 1;
        float f = d - length(l);
        if (abs(f) < p.tolerance) break;
        if (f > 0.0f) {
            if (lastSide == 1 && haveB) fb *= 0.5f;
            ta = t;
            fa = f;
            haveA = !isInfiniteDistance(d, p.dInf);
            lastSide = 1;
        } else {
            if (lastSide == -1 && haveA) fa *= 0.5f;
            tb = t;
            fb = f;
            haveB = true;
            lastSide = -1;
        }
    }
    return finishRectified(layer, l, d, fetches, p.dInf);
}
#endif

#if HAS_AVGDIST
// One fetch at x + d-bar l: exact when the object lies at the layer's mean distance.
LayerHit lookupAvgDist(int layer, vec3 x, vec3 lhat, ProbeLookupParams p) {
    vec3 l = x + layerAvgDistance(layer) * lhat;
    return finishRectified(layer, l, fetchDistance(layer, l), 1, p.dInf);
}
#endif

#if HAS_LAYERS
// Whether the ray x + t lhat (t >= 0) can meet the layer's bounding box: a layer the ray
// misses costs no fetch at all, which is what keeps many layers affordable.
bool layerMayHit(int layer, vec3 x, vec3 lhat) {
    vec3 s = vec3(lhat.x >= 0.0f ? 1.0f : -1.0f, lhat.y >= 0.0f ? 1.0f : -1.0f,
                  lhat.z >= 0.0f ? 1.0f : -1.0f);
    vec3 inv = s / max(abs(lhat), vec3(1e-12f));
    vec3 t1 = (layerBoxMin(layer) - x) * inv;
    vec3 t2 = (layerBoxMax(layer) - x) * inv;
    vec3 tNear = min(t1, t2);
    vec3 tFar = max(t1, t2);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0f));
    float leave = min(min(tFar.x, tFar.y), tFar.z);
    return enter <= leave;
}
#endif

LayerHit lookupLayer(int method, int layer, vec3 x, vec3 lhat, ProbeLookupParams p) {
#if HAS_BISECTION
    if (method == kMethodBisection) return lookupBisection(layer, x, lhat, p);
#endif
#if HAS_SECANT
    if (method == kMethodSecant) return lookupSecant(layer, x, lhat, p);
#endif
#if HAS_AVGDIST
    if (method == kMethodAvgDist) return lookupAvgDist(layer, x, lhat, p);
#endif
#if HAS_BOXPROJ
    if (method == kMethodBoxProj) {
        vec3 l = x + boxExitDistance(x, lhat, p.boxMin, p.boxMax) * lhat;
        return makeHit(fetchRadiance(layer, l), true, 1);
    }
#endif
    // Classic environment map: direction only. The composite (layer 0) holds the sky where
    // it sees nothing, so it always answers; an object layer of distant things (layered
    // mode) answers only where it has something, else the layers behind it and the sky do.
    if (layer == 0) return makeHit(fetchRadiance(layer, lhat), true, 1);
    return finishRectified(layer, lhat, fetchDistance(layer, lhat), 1, p.dInf);
}

// Radiance seen from probe-local point x along the unit reflected direction lhat.
vec3 probeRadiance(vec3 x, vec3 lhat, ProbeLookupParams p, INOUT(int) fetches) {
#if HAS_LAYERS
    // Near to far: the first layer with a hit occludes everything behind it.
    for (int i = 1; i <= p.layerCount; ++i) {
        if (!layerMayHit(i, x, lhat)) continue;
        LayerHit h = lookupLayer(layerMethod(i), i, x, lhat, p);
        fetches += h.fetches;
        if (h.hit) return h.radiance;
    }
    fetches += 1;
    return fetchSky(lhat);
#else
    LayerHit h = lookupLayer(p.method, 0, x, lhat, p);
    fetches += h.fetches;
    if (h.hit) return h.radiance;
    fetches += 1;
    return fetchSky(lhat);
#endif
}

#endif
