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

struct LayerHit {
    vec3 radiance;
    bool hit;    // false: this layer has nothing in that direction (d_inf)
    int fetches; // texture fetches spent (distance and radiance)
    float t;     // distance along the ray to the surface found (layers compete on it)
};

#endif
