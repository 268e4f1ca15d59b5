// Line 2
#include "tests/gpu/shaders/helpers.glsl"
#include "tests/gpu/shaders/helpers.glsl"
layout(location = 0) out vec4 fragColor;

void main() {
    fragColor = nestedColour();
    fragColor.x = undeclaredName; // line 8: the error
}
