#pragma once
// The GGX directional albedo table (engine/image/ggx_albedo.h) as the R32F texture the
// shaders' fetchGgxAlbedo reads with texelFetch (engine/image/ggx_albedo.glsl.h).
#include "engine/gpu/gl_objects.h"

namespace specula::gpu {

Texture createGgxAlbedoTexture();

} // namespace specula::gpu
