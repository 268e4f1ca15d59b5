#pragma once
// C++ side of engine/math/shading.glsl.h: the shared functions in specula::glsl with
// internal linkage, so any number of translation units may include them.
#include "engine/core/glsl_host.h"

namespace specula::glsl {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "engine/math/shading.glsl.h"
#pragma GCC diagnostic pop
} // namespace
} // namespace specula::glsl
