// Shared by GLSL and C++ (see engine/core/glsl_host.h): the types and constants of
// distance_lookup.glsl.h, apart so the C++ side defines them once for all its twins.
#ifndef SPECULA_DISTANCE_LOOKUP_TYPES_GLSL_H
#define SPECULA_DISTANCE_LOOKUP_TYPES_GLSL_H

#include "components/reflection_probe/distance/shaders/distance_params.glsl.h"

SHARED_CONST int kMethodEnvmap = 0;
SHARED_CONST int kMethodBoxProj = 1;
SHARED_CONST int kMethodBisection = 2;
SHARED_CONST int kMethodSecant = 3;
SHARED_CONST int kMethodAvgDist = 4;
SHARED_CONST int kMethodMarch = 5;

struct LayerHit {
    vec3 radiance;
    bool hit;    // false: this layer has nothing in that direction (d_inf)
    int fetches; // texture fetches spent (distance and radiance)
    float t;     // distance along the ray to the surface found (layers compete on it)
    // The probe-local point whose texel gave the radiance: the search's last point, on the
    // stored surface's direction, where x + t lhat (that surface point projected onto the
    // ray) is not while the search stops short of exact. A glossy read takes the chain here,
    // so the chain and the mirror read the same texel (distance_glossy_lookup.glsl.h).
    vec3 at;
};

// A probe's lookup with its verdict on whether it sees what it proposes
// (distance_seen.glsl.h), what a level blends (distance_level_blend.glsl.h).
struct SeenSample {
    vec3 radiance;
    // How surely the probe sees what it proposes, in [0, 1]: 1 when the reflector point lies
    // in front of its stored surface and (rectifying methods) the hit agrees with its stored
    // distances within a band of kSeenRelativeSlack |q| + d_e; falling linearly to 0 at
    // twice the band, so a verdict near the edge fades instead of flipping between frames.
    float visibility;
    bool seen;   // visibility >= 0.5
    int fetches; // texture fetches spent
    float t;     // along the ray to the hit proposed (d_inf: the sky)
};

// A glossy lookup (distance_glossy_lookup.glsl.h): the prefiltered chain read at the hit.
struct GlossySample {
    vec3 radiance;
    float level; // the chain level read (0 for a mirror: no chain read at all)
    float t;     // along the ray to the hit whose direction the chain was read at (d_inf: none)
    bool hit;    // a surface was found (always for envmap and boxproj)
    int fetches; // texture fetches spent (distance, radiance and chain texels)
};

#endif
