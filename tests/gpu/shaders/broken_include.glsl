// A helper with a deliberate type error on line 5.
float brokenHelper(float x) {
    float y = x * 2.0;
    // the next line assigns a vec3 to a float
    float z = vec3(y);
    return z;
}
