// Shared by GLSL and C++ (see engine/core/glsl_host.h): what the level shader knows of each
// of a level's distance probes, one std140 uniform block for the whole level (the rules of
// distance_params.glsl.h). Probes are stored in blend order (probe_volume.h blendsBefore),
// so a shader that walks them by index walks them in the order the engine blend wants.
#ifndef SPECULA_DISTANCE_LEVEL_PARAMS_GLSL_H
#define SPECULA_DISTANCE_LEVEL_PARAMS_GLSL_H

#include "components/reflection_probe/distance/shaders/distance_params.glsl.h"

// Probes one view can hold: 64 x 160 bytes fills 10 KiB of the 16 KiB every GL 4.5 driver
// must allow a uniform block. A level with more is refused with this limit (the texture
// array's layers, 6 per probe, are the other limit).
SHARED_CONST int kMaxLevelProbes = 64;
// The uniform-buffer binding point of the level block (the single-probe block is on 0).
SHARED_CONST int kLevelParamsBinding = 1;

// How a pixel blends the level's probes (distance_level_blend.glsl.h).
SHARED_CONST int kLevelBlendNearest = 0;
SHARED_CONST int kLevelBlendEngine = 1;
SHARED_CONST int kLevelBlendVisibility = 2;
// Probes one pixel blends at most (K is a shader permutation, 4 by default).
SHARED_CONST int kMaxLevelK = 8;

struct LevelProbeParams {
    DistanceParams lookup;         // the probe's own lookup (its centre, box, range, d_e)
    DistanceLayerParams composite; // layer 0's entry (d-bar)
    vec3 influenceMin;             // box influence, world space
    int influenceShape;            // kInfluenceBox or kInfluenceSphere
    vec3 influenceMax;
    float influenceRadius; // sphere influence
    vec3 influenceCentre;  // (its centre, world space)
    float blendDistance;   // metres over which the influence rises from 0 to 1
};

struct LevelParamsBlock {
    LevelProbeParams probes[kMaxLevelProbes];
};

#ifdef __cplusplus
static_assert(offsetof(LevelProbeParams, composite) == 64 &&
              offsetof(LevelProbeParams, influenceMin) == 112 &&
              offsetof(LevelProbeParams, influenceShape) == 124 &&
              offsetof(LevelProbeParams, influenceMax) == 128 &&
              offsetof(LevelProbeParams, influenceCentre) == 144 &&
              offsetof(LevelProbeParams, blendDistance) == 156 && sizeof(LevelProbeParams) == 160);
static_assert(sizeof(LevelParamsBlock) == 160 * kMaxLevelProbes);
#endif

#endif
