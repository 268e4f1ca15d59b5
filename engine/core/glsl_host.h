#pragma once
// Lets a `*.glsl.h` file compile as C++ as well as GLSL, so shading and lookup code is
// written once and the C++ copy is the CPU twin of the shader. Include this, then include
// the shared file inside `namespace specula::glsl { ... }`.
//
// Rules for shared files: float literals carry an `f` suffix (GLSL accepts it too), no
// `in`/`out` qualifiers (use INOUT), no swizzle assignment, no implicit int->float.
#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#define INOUT(T) T&
#define SHARED_CONST static constexpr

namespace specula::glsl {
using namespace glm;
using uint = unsigned;
inline float inversesqrt(float x) {
    return 1.0f / std::sqrt(x);
}
} // namespace specula::glsl
