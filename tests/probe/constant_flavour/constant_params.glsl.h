// Shared by GLSL and C++ (engine/core/glsl_host.h): the constant-colour test flavour's
// parameter block (std140) and its whole lookup, which the C++ side runs as the twin.
#ifndef SPECULA_CONSTANT_PARAMS_GLSL_H
#define SPECULA_CONSTANT_PARAMS_GLSL_H

// Binding point of the block, apart from the distance flavour's.
SHARED_CONST int kConstantParamsBinding = 3;

struct ConstantParams {
    vec3 colour; // the cooked colour
    float gain;  // the settings' scale
};

// Every reflected ray sees the same radiance.
vec3 constantRadiance(ConstantParams p) {
    return p.colour * p.gain;
}

#ifdef __cplusplus
static_assert(offsetof(ConstantParams, gain) == 12 && sizeof(ConstantParams) == 16);
#endif

#endif
