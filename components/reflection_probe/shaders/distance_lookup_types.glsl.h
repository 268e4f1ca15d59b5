// Shared by GLSL and C++ (see engine/core/glsl_host.h): the types and constants of
// distance_lookup.glsl.h, apart so the C++ side defines them once for all its twins.
#ifndef SPECULA_DISTANCE_LOOKUP_TYPES_GLSL_H
#define SPECULA_DISTANCE_LOOKUP_TYPES_GLSL_H

SHARED_CONST int kMethodEnvmap = 0;
SHARED_CONST int kMethodBoxProj = 1;
SHARED_CONST int kMethodBisection = 2;
SHARED_CONST int kMethodSecant = 3;
SHARED_CONST int kMethodAvgDist = 4;

struct ProbeLookupParams {
    vec3 boxMin; // probe-local environment box (box projection)
    vec3 boxMax;
    float range;     // D: every hit lies within (x, x + 2D l)
    float tolerance; // d_e: stop when |stored - |l|| < d_e
    float dInf;      // sentinel distance of texels that see nothing
    int maxSteps;    // N = ceil(log2(2D / d_e))
    int method;      // single-layer method; layered mode reads layerMethod()
    int layerCount;  // object layers after the composite
};

struct LayerHit {
    vec3 radiance;
    bool hit;    // false: this layer has nothing in that direction (d_inf)
    int fetches; // texture fetches spent (distance and radiance)
    float t;     // distance along the ray to the surface found (layers compete on it)
};

#endif
