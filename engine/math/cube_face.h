#pragma once
// C++ side of engine/math/cube_face.glsl.h (see engine/math/shading.h for why this way).
#include "engine/core/glsl_host.h"

namespace specula::glsl {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "engine/math/cube_face.glsl.h"
#pragma GCC diagnostic pop
} // namespace
} // namespace specula::glsl
