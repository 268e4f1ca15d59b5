out vec3 vColour;
void main() {
    vColour = vec3(1.0);
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
