// Shared by GLSL and C++ (see engine/core/glsl_host.h): every parameter of a distance
// probe's lookup, laid out std140 so the C++ struct is uploaded as is into the uniform
// block the shader reads (shaders/distance_probe_gpu.glsl), and read by the CPU twin too.
// Written once: no copier between a config, a parameter struct and loose uniforms.
//
// std140 rules kept by hand: a vec3 is followed by one 4-byte scalar (it fills the vec3's
// 16-byte slot), structs are multiples of 16 bytes, padding is named, no bool (4 bytes in
// GLSL, 1 in C++). The static_asserts below hold the C++ side to it.
#ifndef SPECULA_DISTANCE_PARAMS_GLSL_H
#define SPECULA_DISTANCE_PARAMS_GLSL_H

// Layer 0 (the composite) and up to 63 object layers: the block's fixed array size.
SHARED_CONST int kMaxDistanceLayers = 64;
// The uniform-buffer binding point the block is read from.
SHARED_CONST int kDistanceParamsBinding = 0;
// The linear march (kMethodMarch, lookupMarch in distance_lookup.glsl.h; Szirmay-Kalos et
// al. 2005): march points along the ray and at most this many secant refinements once one
// has passed the surface. Constants rather than block fields: the block is a full std140
// layout shared with the PEM and level lookups, and 30 and 6 are what an open engine
// implementation of the method uses. Its fetches are at most their sum plus the radiance.
SHARED_CONST int kMarchSteps = 30;
SHARED_CONST int kMarchRefineSteps = 6;
// Bisection and secant on the composite (layer 0) first march this many points of the same
// projection-uniform parameterisation to the first place where the stored distance turns
// shorter than |l| (bracketFirstCrossing in distance_lookup.glsl.h), then search inside that
// stretch only: the composite holds every object, so along a ray that passes behind a nearer
// one f changes sign more than once, and a search over the whole span may settle on a later
// crossing. Their fetches per layer are at most this plus N. 20, not 8 (issue 15): at
// 1024x768 with 256^2 faces, 8 points stepped over thin objects (the first crossing lay
// before the bracket, or no crossing was seen at all): 1.6-1.9 % of the room's reflector
// rays, where bisection's squared error above the exact first crossing's was 25-34 % of its
// whole; 8 % of truck_room's, 22 %. With 20 the CPU twin of bisection reaches the
// march's error on the room and within 0.35 dB of it on truck_room at d_e 0.1 (above it at
// 0.01), in 18-21 fetches against its 25-26. Counts of 12-24, a second pass between the
// points where none crossed, and counts following the texels the ray's projection crosses
// measured no better at equal fetches (thin objects alias with the step: the error is not
// monotonic in the count). Swept again over 4 scenes (the gallery among them) x 2 sizes x d_e
// 0.1 / 0.01 with the safeguarded secant: 24 points would raise the median by 0.06 dB for 3
// more fetches, one scene moving +2.7 dB and another -0.15 (aliasing, not a trend): kept at
// 20, the count the first two scenes chose, rather than tuned to the bench.
SHARED_CONST int kBracketSteps = 20;

// What the lookup of every layer reads.
struct DistanceParams {
    vec3 boxMin;     // probe-local environment box (box projection)
    float range;     // D: every hit lies within (x, x + 2D l)
    vec3 boxMax;     // (its far corner)
    float tolerance; // d_e: stop when |stored - |l|| < d_e
    vec3 centre;     // world position of the probe (reflector points are made local)
    float dInf;      // sentinel distance of texels that see nothing
    int maxSteps;    // N = ceil(log2(2D / d_e))
    int method;      // single-layer method (kMethod*); layered mode reads layers[i].method
    int layerCount;  // object layers after the composite (layered mode)
    int faceRes;     // texels along a cube face edge
};

// One layer's entry (index = layer; entry 0, the composite, has no method of its own).
struct DistanceLayerParams {
    vec3 boxMin; // probe-local bounds of the layer
    int method;  // kMethod* of an object layer in layered mode
    vec3 boxMax;
    float avgDistance; // d-bar
    // Closest that this layer and every later one come to the probe centre: once a hit is
    // nearer than that, no later layer can occlude it and the layered loop ends.
    float reach;
    int pad0;
    int pad1;
    int pad2;
};

struct DistanceParamsBlock {
    DistanceParams params;
    DistanceLayerParams layers[kMaxDistanceLayers];
};

#ifdef __cplusplus
// Each vec3 shares its 16-byte slot with the 4-byte scalar after it.
static_assert(offsetof(DistanceParams, range) == 12 && offsetof(DistanceParams, boxMax) == 16);
static_assert(offsetof(DistanceParams, tolerance) == 28 && offsetof(DistanceParams, centre) == 32);
static_assert(offsetof(DistanceParams, dInf) == 44 && offsetof(DistanceParams, maxSteps) == 48);
static_assert(offsetof(DistanceParams, faceRes) == 60 && sizeof(DistanceParams) == 64);
static_assert(offsetof(DistanceLayerParams, method) == 12 &&
              offsetof(DistanceLayerParams, boxMax) == 16 &&
              offsetof(DistanceLayerParams, avgDistance) == 28 &&
              offsetof(DistanceLayerParams, reach) == 32 && sizeof(DistanceLayerParams) == 48);
// An array of structs in std140 strides by the struct's size rounded up to 16: 48.
static_assert(offsetof(DistanceParamsBlock, layers) == 64 &&
              sizeof(DistanceParamsBlock) == 64 + 48 * kMaxDistanceLayers);
#endif

#endif
