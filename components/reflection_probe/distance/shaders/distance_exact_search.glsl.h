// Shared by the C++ twin only (see engine/core/glsl_host.h): its exact search, included by
// distance_lookup.glsl.h under SPECULA_EXACT_SEARCH_HOOK, which no shader defines. Part of
// distance_lookup.glsl.h, included by it only and inside its guard, so each of the twin's two
// inclusions (with and without layers) gets its copy.

// The CPU twin's error-budget experiment (CpuDistanceProbe::Experiment::exactSearch), never
// compiled into a shader: the method's own way to the hit replaced by the exact first
// crossing of f = stored distance - |l| from > 0 to <= 0 over the span, found by a
// projection-uniform march dense enough to put about four points in every texel the ray's
// projection crosses (the projection of 2D spans at most half the sphere, two faces' edges),
// then bisected to float precision. No crossing: the span's end answers through the d_inf
// rule, as the searches do. The includer provides bool exactSearchOn().
LayerHit lookupExact(int layer, vec3 x, vec3 lhat, DistanceParams p, RaySpan span) {
    MarchFrame m = marchFrame(x, lhat, span);
    int points = max(64, 8 * p.faceRes);
    int fetches = 0;
    float ta = span.t0;
    float tb = span.t1;
    bool crossed = false;
    for (int k = 1; k <= points && !crossed; ++k) {
        float t = marchT(span, m, k, points);
        vec3 l = x + t * lhat;
        fetches += 1;
        if (fetchDistance(layer, l) - length(l) <= 0.0f) {
            tb = t;
            crossed = true;
        } else {
            ta = t;
        }
    }
    for (int n = 0; crossed && n < 48 && tb - ta > 1e-7f * max(1.0f, tb); ++n) {
        float mid = 0.5f * (ta + tb);
        vec3 l = x + mid * lhat;
        fetches += 1;
        if (fetchDistance(layer, l) - length(l) > 0.0f) {
            ta = mid;
        } else {
            tb = mid;
        }
    }
    vec3 l = x + tb * lhat;
    return finishRectified(layer, x, lhat, l, fetchDistance(layer, l), fetches + 1, p.dInf);
}
