// Shared by GLSL and C++ (see engine/core/glsl_host.h): the projection-uniform march points
// and the march to the first crossing, where bisection and secant on the composite and the
// march (the peer) start. Part of distance_lookup.glsl.h, included by it only and inside its
// guard, so each of the twin's two inclusions (with and without layers) gets its copy.

// March points uniform in the ray's projection onto the cube map (see lookupMarch): point k
// of `count` lies at t0 + s a / (1 - a) with a = aMax k / count, the last one at t1.
struct MarchFrame {
    float s;
    float aMax;
};

MarchFrame marchFrame(vec3 x, vec3 lhat, RaySpan span) {
    float width = max(span.t1 - span.t0, 0.0f);
    MarchFrame m;
    m.s = max(max(length(x + span.t0 * lhat), 0.25f * width), 1e-6f);
    m.aMax = width / (width + m.s); // < 1: the last point lands on t1
    return m;
}

float marchT(RaySpan span, MarchFrame m, int k, int count) {
    float a = m.aMax * float(k) / float(count);
    return span.t0 + m.s * a / (1.0f - a);
}

// What a march to the first crossing found: the last point before the surface (ta, with
// f = fa > 0; haveA when its stored distance is finite, so fa is a usable secant end) and
// the first beyond it (tb, fb < 0; crossed), or a point within d_e of its stored distance
// (converged), or neither (the whole span stayed in front of the stored surface). l and d:
// the last point fetched and its stored distance.
struct Bracket {
    float ta;
    float fa;
    bool haveA;
    float tb;
    float fb;
    bool crossed;
    bool converged;
    vec3 l;
    float d;
    int fetches;
};

// The span itself as a bracket nothing has been fetched for.
Bracket openBracket(vec3 x, vec3 lhat, RaySpan span, DistanceParams p) {
    Bracket b;
    b.ta = span.t0;
    b.fa = 0.0f;
    b.haveA = false;
    b.tb = span.t1;
    b.fb = 0.0f;
    b.crossed = false;
    b.converged = false;
    b.l = x + span.t0 * lhat;
    b.d = p.dInf;
    b.fetches = 0;
    return b;
}

// Marches `count` projection-uniform points along the span until f = stored distance - |l|
// turns from > 0 to < 0: the first crossing, the surface the ray meets first. Where the ray
// passes behind a nearer object as seen from the centre, f turns negative, positive again
// and negative once more at the farther surface; a search that starts mid-span can settle
// on that later crossing.
Bracket bracketFirstCrossing(int layer, vec3 x, vec3 lhat, DistanceParams p, RaySpan span,
                             int count) {
    MarchFrame m = marchFrame(x, lhat, span);
    Bracket b = openBracket(x, lhat, span, p);
    for (int k = 1; k <= count; ++k) {
        float t = marchT(span, m, k, count);
        b.l = x + t * lhat;
        b.d = fetchDistance(layer, b.l);
        b.fetches += 1;
        float f = b.d - length(b.l);
        if (abs(f) < p.tolerance) {
            b.converged = true;
            break;
        }
        if (f < 0.0f) {
            b.tb = t;
            b.fb = f;
            b.crossed = true;
            break;
        }
        b.ta = t;
        b.fa = f;
        b.haveA = !isInfiniteDistance(b.d, p.dInf);
    }
    return b;
}
