layout(location = 0) out vec4 fragColor;

void main() {
#ifdef RED
    fragColor = vec4(1.0, 0.0, 0.0, 1.0);
#else
    fragColor = vec4(0.0, 1.0, 0.0, 1.0);
#endif
#ifdef BLUE_LEVEL
    fragColor.b = BLUE_LEVEL;
#endif
}
