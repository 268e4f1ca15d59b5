// Two triangles covering uRect = (x0, y0, x1, y1) in normalised device coordinates.
uniform vec4 uRect;

void main() {
    const vec2 corners[6] = vec2[](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1),
                                   vec2(0, 1));
    vec2 c = corners[gl_VertexID];
    gl_Position = vec4(mix(uRect.xy, uRect.zw, c), 0.0, 1.0);
}
