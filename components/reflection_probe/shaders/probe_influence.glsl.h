// Shared by GLSL and C++ (see engine/core/glsl_host.h): a probe's influence volume and its
// weight at a point, what a pixel blending several probes computes per probe
// (probe_volume.h holds the same volume as plain data; its influenceDepth runs this code).
#ifndef SPECULA_PROBE_INFLUENCE_GLSL_H
#define SPECULA_PROBE_INFLUENCE_GLSL_H

SHARED_CONST int kInfluenceBox = 0;
SHARED_CONST int kInfluenceSphere = 1;

// How far p lies inside the volume: the distance to the nearest face of the box
// [boxMin, boxMax], or to the surface of the sphere (centre, radius); negative outside.
float influenceDepthOf(int shape, vec3 boxMin, vec3 boxMax, vec3 centre, float radius, vec3 p) {
    if (shape == kInfluenceSphere) return radius - length(p - centre);
    vec3 inside = min(p - boxMin, boxMax - p);
    return min(min(inside.x, inside.y), inside.z);
}

// 0 outside, rising linearly over blendDistance from the boundary to 1 (a step at the
// boundary when blendDistance is 0).
float influenceWeightOf(float depth, float blendDistance) {
    if (depth < 0.0f) return 0.0f;
    if (blendDistance <= 0.0f) return 1.0f;
    return min(1.0f, depth / blendDistance);
}

#endif
