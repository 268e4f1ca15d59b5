// No include guard on purpose: the expander includes each file once per stage.
float helperScale(float x) {
    return 2.0 * x;
}

#include "tests/gpu/shaders/nested.glsl"
