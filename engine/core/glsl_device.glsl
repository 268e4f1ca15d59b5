// GLSL side of engine/core/glsl_host.h: the macros shared `*.glsl.h` files use.
#ifndef SPECULA_GLSL_DEVICE
#define SPECULA_GLSL_DEVICE
#define INOUT(T) inout T
#define SHARED_CONST const
#endif
