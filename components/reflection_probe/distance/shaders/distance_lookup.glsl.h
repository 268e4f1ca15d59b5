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
//   float layerReach(int layer)                the closest layers layer.. come to the centre
// and defines HAS_ENVMAP, HAS_BOXPROJ, HAS_BISECTION, HAS_SECANT, HAS_AVGDIST, HAS_MARCH,
// HAS_LAYERS as 0 or 1: a method the probe does not use is not compiled into its shader.
//
// Layer 0 is the composite (every environment object, sky in the texels that see none);
// layers 1..layerCount are single objects or groups, sorted near to far.
#ifndef SPECULA_DISTANCE_LOOKUP_GLSL_H
#define SPECULA_DISTANCE_LOOKUP_GLSL_H

#include "components/reflection_probe/distance/shaders/distance_lookup_types.glsl.h"

bool isInfiniteDistance(float d, float dInf) {
    return d >= 0.5f * dInf;
}

LayerHit makeHit(vec3 radiance, bool hit, int fetches, float t, vec3 at) {
    LayerHit h;
    h.radiance = radiance;
    h.at = at;
    h.hit = hit;
    h.fetches = fetches;
    h.t = t;
    return h;
}

// Finishes a rectified lookup that ended at probe-local point l, where the stored distance
// is d: the d_inf rule says a lookup that ends on a texel that sees nothing has no hit in
// this layer, which is what keeps silhouettes from smearing. The hit's ray distance is
// that of the stored surface point d l/|l| projected onto the ray x + t lhat.
LayerHit finishRectified(int layer, vec3 x, vec3 lhat, vec3 l, float d, int fetches, float dInf) {
    if (isInfiniteDistance(d, dInf)) return makeHit(vec3(0.0f), false, fetches, dInf, l);
    float t = dot(d * normalize(l) - x, lhat);
    return makeHit(fetchRadiance(layer, l), true, fetches + 1, t, l);
}

#if HAS_BOXPROJ
// Distance along l from x (inside the box) to the box wall it leaves through.
float boxExitDistance(vec3 x, vec3 l, vec3 boxMin, vec3 boxMax) {
    // Keep the sign of each component but never divide by less than 1e-8 in magnitude.
    vec3 s =
        vec3(l.x >= 0.0f ? 1.0f : -1.0f, l.y >= 0.0f ? 1.0f : -1.0f, l.z >= 0.0f ? 1.0f : -1.0f);
    vec3 safeL = s * max(abs(l), vec3(1e-8f));
    vec3 t1 = (boxMax - x) / safeL;
    vec3 t2 = (boxMin - x) / safeL;
    vec3 tFar = max(t1, t2);
    return max(min(min(tFar.x, tFar.y), tFar.z), 0.0f);
}
#endif

// A search for the hit along x + t lhat within t in [t0, t1] in at most `steps` fetches:
// the whole range (0, 2D) with N = ceil(log2(2D / d_e)) steps for a single layer, the
// stretch of the ray inside an object layer's bounding box for layered lookups.
struct RaySpan {
    float t0;
    float t1;
    int steps;
};

RaySpan makeSpan(float t0, float t1, int steps) {
    RaySpan s;
    s.t0 = t0;
    s.t1 = t1;
    s.steps = steps;
    return s;
}

// Steps that bring a span of the given width down to d_e: the counterpart of N for a
// narrower span. In logarithms, and clamped as a float, so d_e -> 0 (FLT_MIN) cannot
// overflow the int.
int spanSteps(float width, DistanceParams p) {
    float n = ceil(log2(max(width, 1e-6f)) - log2(p.tolerance));
    return int(clamp(n, 1.0f, float(p.maxSteps)));
}

// The march to the first crossing (MarchFrame, bracketFirstCrossing), its own file for
// length; no guard of its own: it is part of this file.
#include "components/reflection_probe/distance/shaders/distance_bracket.glsl.h"

#if HAS_BISECTION || HAS_AVGDIST
// Bisection: start mid-span (t = D for the whole range) and move by half the remaining
// width towards the surface until the stored distance agrees with |l| within d_e
// (condition 1) or the steps run out. The average-distance correction is its one-step
// case on the empty span at avgDistanceT (one fetch), so a shader that mixes the two
// methods over its layers runs a single loop.
LayerHit lookupBisection(int layer, vec3 x, vec3 lhat, DistanceParams p, RaySpan span) {
    float step = 0.5f * (span.t1 - span.t0);
    vec3 l = x + (span.t0 + step) * lhat;
    float d = p.dInf;
    int fetches = 0;
    for (int n = 1; n <= span.steps; ++n) {
        d = fetchDistance(layer, l);
        fetches += 1;
        float delta = d - length(l);
        if (abs(delta) < p.tolerance || n == span.steps) break;
        step *= 0.5f;
        l += (delta > 0.0f ? step : -step) * lhat;
    }
    return finishRectified(layer, x, lhat, l, d, fetches, p.dInf);
}
#endif

#if HAS_SECANT
// Same bracket search as bisection (identical first steps), but once the surface is
// bracketed by a point before it (f > 0) and one beyond it (f < 0) the next t comes from
// the secant through both, with the Illinois weighting so one end cannot stall. A secant
// step that leaves the bracket, or an end that saw only d_inf, falls back to the midpoint,
// and so does the step after one that did not halve the bracket (Dekker's safeguard): the
// nearest-texel distance is a staircase along the ray, where a secant can creep towards
// one end while its steps run out far from the crossing (issue 15: that held 9-37 % of
// secant's error over the exact search). So the bracket at least halves every two steps,
// and the search ends where the stored distance agrees with |l| within d_e, or the bracket
// is narrower than d_e (the crossing's position is known as well as bisection knows it),
// or after 2 `steps` fetches. Starts from bracket b (its ends and fetches so far).
LayerHit secantIn(int layer, vec3 x, vec3 lhat, DistanceParams p, Bracket b, int steps) {
    float ta = b.ta;
    float fa = b.fa;
    bool haveA = b.haveA; // ta: last t before the surface with a finite stored distance
    float tb = b.tb;
    float fb = b.fb;
    bool haveB = b.crossed; // tb: last t beyond the surface
    int lastSide = 0;
    float widthBefore = 2.0f * (tb - ta); // the bracket before the last step: none yet
    vec3 l = x + 0.5f * (ta + tb) * lhat;
    float d = p.dInf;
    int fetches = b.fetches;
    for (int n = 1; n <= 2 * steps; ++n) {
        float width = tb - ta;
        float t = 0.5f * (ta + tb);
        bool secantStep = haveA && haveB && width <= 0.5f * widthBefore;
        widthBefore = secantStep ? width : 2.0f * width; // a midpoint halves it by itself
        if (secantStep) {
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
        if (tb - ta < p.tolerance) break;
    }
    return finishRectified(layer, x, lhat, l, d, fetches, p.dInf);
}

LayerHit lookupSecant(int layer, vec3 x, vec3 lhat, DistanceParams p, RaySpan span) {
    return secantIn(layer, x, lhat, p, openBracket(x, lhat, span, p), span.steps);
}
#endif

#if HAS_MARCH
// The peer the searches above are measured against: Szirmay-Kalos et al. 2005,
// "Approximate ray-tracing on the GPU with distance impostors" (GPU Gems 3, ch. 17). March
// kMarchSteps points along the span until f = stored distance - |l| turns from > 0 to < 0
// (the ray has passed the surface), then at most kMarchRefineSteps secant (false position)
// steps between the last two march points; a march or refinement point within d_e of its
// stored distance ends the search early. No crossing in the span: the last march point
// (t1) answers through the same d_inf rule as the other searches.
//
// Parameterisation: like Szirmay-Kalos, the march is uniform in the ray's projection, not
// in t. With u = t - t0 and the ray's start q = x + t0 lhat, the point q + u lhat has the
// direction of (1 - a) q + a s lhat for u = s a / (1 - a): uniform steps in a are uniform
// steps along the straight segment from q to s lhat, whose central projection is what the
// cube map indexes, so the steps are dense near the start (where the direction from the
// centre turns fastest) and sparse far out (where it hardly changes any more). The scale s
// is |q| (the segment then joins two points equally far from the centre, near uniform in
// angle) but at least a quarter of the span: from a start near the centre the direction
// barely turns, and s = |q| -> 0 would put every step at the start. For the single-layer
// span (0, 2D) that is s = max(|x|, D/2), the first step at about D/60 and the last one
// about 0.29 D long (uniform steps would be 2D/30 = 0.067 D).
LayerHit lookupMarch(int layer, vec3 x, vec3 lhat, DistanceParams p, RaySpan span) {
    Bracket b = bracketFirstCrossing(layer, x, lhat, p, span, kMarchSteps);
    if (!b.crossed) return finishRectified(layer, x, lhat, b.l, b.d, b.fetches, p.dInf);
    float ta = b.ta;
    float fa = b.fa;
    bool haveA = b.haveA; // ta: last point before the surface with a finite distance
    float tb = b.tb;
    float fb = b.fb;
    vec3 l = b.l;
    float d = b.d;
    int fetches = b.fetches;
    for (int n = 1; n <= kMarchRefineSteps; ++n) {
        // The secant through both ends; the midpoint where the near end saw only d_inf (or
        // is the span start, never fetched) or rounding puts the secant outside the bracket.
        float t = 0.5f * (ta + tb);
        if (haveA) {
            float candidate = ta + fa * (tb - ta) / (fa - fb);
            if (candidate > ta && candidate < tb) t = candidate;
        }
        l = x + t * lhat;
        d = fetchDistance(layer, l);
        fetches += 1;
        float f = d - length(l);
        if (abs(f) < p.tolerance) break;
        if (f > 0.0f) {
            ta = t;
            fa = f;
            haveA = !isInfiniteDistance(d, p.dInf);
        } else {
            tb = t;
            fb = f;
        }
    }
    return finishRectified(layer, x, lhat, l, d, fetches, p.dInf);
}
#endif

#if HAS_LAYERS
// Where the ray x + t lhat (t >= 0) enters and leaves the layer's bounding box; enter > leave
// when it misses. A layer the ray misses, or enters only behind a nearer hit, costs no fetch
// at all, which is what keeps many layers affordable; one it meets is searched only over
// the stretch inside the box, where the directions from the centre see the object (the
// rest of the ray sees d_inf, which would lead the search away from the object).
vec2 layerSpan(int layer, vec3 x, vec3 lhat) {
    vec3 s = vec3(lhat.x >= 0.0f ? 1.0f : -1.0f, lhat.y >= 0.0f ? 1.0f : -1.0f,
                  lhat.z >= 0.0f ? 1.0f : -1.0f);
    vec3 inv = s / max(abs(lhat), vec3(1e-12f));
    vec3 t1 = (layerBoxMin(layer) - x) * inv;
    vec3 t2 = (layerBoxMax(layer) - x) * inv;
    vec3 tNear = min(t1, t2);
    vec3 tFar = max(t1, t2);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0f));
    float leave = min(min(tFar.x, tFar.y), tFar.z);
    return vec2(enter, leave);
}
#endif

#if HAS_BISECTION || HAS_SECANT
// Bisection or secant on the composite: march kBracketSteps points to the first crossing
// (bracketFirstCrossing), then search only between the last point before it and the first
// beyond it, in as many steps as that stretch needs to come down to d_e. A march that ends
// within d_e of the stored surface answers there. One that sees no crossing answers at its
// last point (the span's end, t1) through the d_inf rule, as the peer's march does: the ray
// left for the sky, or passed something thinner than a march step. The search over the
// whole span that used to follow found such slivers behind 8 points, but behind 20 it
// changed no error on the room or truck_room (measured, issue 15) and cost N fetches on
// every ray that sees the sky. At most kBracketSteps + N distance fetches for bisection,
// kBracketSteps + 2N for secant (secantIn).
LayerHit lookupFirstCrossing(int method, vec3 x, vec3 lhat, DistanceParams p, RaySpan span) {
    Bracket b = bracketFirstCrossing(0, x, lhat, p, span, kBracketSteps);
    if (!b.crossed) return finishRectified(0, x, lhat, b.l, b.d, b.fetches, p.dInf);
    int steps = spanSteps(b.tb - b.ta, p);
#if HAS_SECANT
    if (method == kMethodSecant) return secantIn(0, x, lhat, p, b, steps);
#endif
#if HAS_BISECTION
    LayerHit h = lookupBisection(0, x, lhat, p, makeSpan(b.ta, b.tb, steps));
    h.fetches += b.fetches;
    return h;
#else
    return makeHit(vec3(0.0f), false, b.fetches, p.dInf, lhat);
#endif
}
#endif

#if HAS_BISECTION || HAS_AVGDIST
// Where along x + t lhat the average-distance correction looks (one fetch): Wang et al.'s
// x + d-bar lhat on the composite (layer 0), whose span is the whole ray. An object layer is
// searched only over the ray's stretch inside its box (layerSpan); there the point is the
// one at d-bar from the centre, where the layer's stored surface lies on average (x + d-bar
// lhat is d-bar from x, which is not the centre once the reflector moves off it), clamped
// into the stretch: a point outside the box cannot lie on the object, and the d_inf it
// reads there made the object vanish from the reflection (issue 15: on the room the rays
// that lost their small object that way held 96 % of the layered lookup's search error).
float avgDistanceT(int layer, vec3 x, vec3 lhat, RaySpan span) {
    float avg = layerAvgDistance(layer);
    if (layer == 0) return avg;
    float xl = dot(x, lhat);
    float disc = xl * xl - dot(x, x) + avg * avg; // |x + t lhat| = d-bar
    return clamp(disc > 0.0f ? sqrt(disc) - xl : avg, span.t0, span.t1);
}
#endif

#ifdef SPECULA_EXACT_SEARCH_HOOK
// The CPU twin's exact search (lookupExact), never compiled into a shader.
#include "components/reflection_probe/distance/shaders/distance_exact_search.glsl.h"
#endif

LayerHit lookupLayer(int method, int layer, vec3 x, vec3 lhat, DistanceParams p, RaySpan span) {
#ifdef SPECULA_EXACT_SEARCH_HOOK
    if (exactSearchOn()) return lookupExact(layer, x, lhat, p, span);
#endif
#if HAS_BISECTION || HAS_SECANT
    // The composite holds every object, so its f may cross zero more than once along a ray;
    // an object layer holds one, searched only within its box (layered mode).
    if (layer == 0 && (method == kMethodBisection || method == kMethodSecant))
        return lookupFirstCrossing(method, x, lhat, p, span);
#endif
#if HAS_BISECTION || HAS_AVGDIST
    if (method == kMethodBisection || method == kMethodAvgDist) {
        RaySpan s = span;
        if (method == kMethodAvgDist) {
            float t = avgDistanceT(layer, x, lhat, span);
            s = makeSpan(t, t, 1);
        }
        return lookupBisection(layer, x, lhat, p, s);
    }
#endif
#if HAS_SECANT
    if (method == kMethodSecant) return lookupSecant(layer, x, lhat, p, span);
#endif
#if HAS_MARCH
    if (method == kMethodMarch) return lookupMarch(layer, x, lhat, p, span);
#endif
#if HAS_BOXPROJ
    if (method == kMethodBoxProj) {
        float t = boxExitDistance(x, lhat, p.boxMin, p.boxMax);
        vec3 at = x + t * lhat;
        return makeHit(fetchRadiance(layer, at), true, 1, t, at);
    }
#endif
#if HAS_ENVMAP
    // Classic environment map: direction only. The composite (layer 0) holds the sky where
    // it sees nothing, so it always answers; an object layer of distant things (layered
    // mode) answers only where it has something, else the layers behind it and the sky do.
    if (layer == 0) return makeHit(fetchRadiance(layer, lhat), true, 1, p.dInf, lhat);
    return finishRectified(layer, x, lhat, lhat, fetchDistance(layer, lhat), 1, p.dInf);
#else
    return makeHit(vec3(0.0f), false, 0, p.dInf, lhat); // no method of this permutation applies
#endif
}

#if HAS_LAYERS
// Object layer i's lookup by its method over the stretch of the ray inside its box, cut at
// 2D (every hit lies within it); no hit, at no fetch, where the ray misses the box or enters
// it only at tMax or beyond (behind a nearer hit).
LayerHit lookupObjectLayer(int i, vec3 x, vec3 lhat, DistanceParams p, float tMax) {
    vec2 span = layerSpan(i, x, lhat);
    float t1 = min(span.y, 2.0f * p.range);
    if (span.x > t1 || span.x >= tMax) return makeHit(vec3(0.0f), false, 0, p.dInf, lhat);
    return lookupLayer(layerMethod(i), i, x, lhat, p,
                       makeSpan(span.x, t1, spanSteps(t1 - span.x, p)));
}
#endif

// The surface seen from probe-local point x along the unit reflected direction lhat: the
// nearest hit along the ray over the object layers (layered), or the composite's lookup by
// p.method; hit = false (t = d_inf) when nothing was found and the sky answers.
LayerHit probeHit(vec3 x, vec3 lhat, DistanceParams p) {
#if HAS_LAYERS
    // The hit nearest along the ray occludes the others. Wang et al. let the first layer
    // with a hit win, which holds for nested shells; per-object layers overlap in depth
    // (the floor is the nearest object below the probe, yet a grazing ray meets it far
    // behind a column), so layers compete on ray distance. Sorted near to far, a nearer
    // layer usually answers first; the box test skips a layer entered only behind the best
    // hit, and the loop ends once no later layer can come nearer: a point of those layers
    // lies at least layerReach from the centre, so at least layerReach - |x| along the ray.
    LayerHit best = makeHit(vec3(0.0f), false, 0, p.dInf, lhat); // t stays d_inf until a hit
    float fromCentre = length(x);
    for (int i = 1; i <= p.layerCount; ++i) {
        if (layerReach(i) - fromCentre >= best.t) break;
        LayerHit h = lookupObjectLayer(i, x, lhat, p, best.t);
        best.fetches += h.fetches;
        if (h.hit && h.t < best.t) {
            best.t = h.t;
            best.radiance = h.radiance;
            best.at = h.at;
            best.hit = true;
        }
    }
    return best;
#else
    return lookupLayer(p.method, 0, x, lhat, p, makeSpan(0.0f, 2.0f * p.range, p.maxSteps));
#endif
}

// Radiance seen from probe-local point x along the unit reflected direction lhat: the hit's,
// else the sky by direction alone.
vec3 probeRadiance(vec3 x, vec3 lhat, DistanceParams p, INOUT(int) fetches) {
    LayerHit h = probeHit(x, lhat, p);
    fetches += h.fetches;
    if (h.hit) return h.radiance;
    fetches += 1;
    return fetchSky(lhat);
}

#endif
