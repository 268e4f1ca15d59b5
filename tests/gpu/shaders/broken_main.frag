#include "tests/gpu/shaders/helpers.glsl"
#include "tests/gpu/shaders/broken_include.glsl"
layout(location = 0) out vec4 fragColor;
void main() { fragColor = vec4(brokenHelper(1.0)); }
