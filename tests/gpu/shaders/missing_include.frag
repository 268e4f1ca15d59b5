layout(location = 0) out vec4 fragColor;
#include "tests/gpu/shaders/does_not_exist.glsl"
void main() { fragColor = vec4(1.0); }
