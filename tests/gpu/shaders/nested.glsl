#include "tests/gpu/shaders/helpers.glsl"
vec4 nestedColour() { return vec4(helperScale(0.25), 0.0, 0.0, 1.0); }
