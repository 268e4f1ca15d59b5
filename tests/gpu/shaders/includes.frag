#include "tests/gpu/shaders/helpers.glsl"
#include "tests/gpu/shaders/nested.glsl"
layout(location = 0) out vec4 fragColor;
void main() { fragColor = nestedColour(); }
