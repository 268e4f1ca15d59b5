in vec4 vColour; // vec3 in the vertex stage: a link-time interface mismatch
layout(location = 0) out vec4 fragColor;
void main() { fragColor = vColour; }
