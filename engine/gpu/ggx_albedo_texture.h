#pragma once
// The GGX directional albedo table (engine/image/ggx_albedo.h) as the R32F texture the
// shaders' fetchGgxAlbedo reads with texelFetch (engine/image/ggx_albedo.glsl.h).
#include "engine/gpu/texture_spec.h"

namespace specula::gpu {

TextureSpec ggxAlbedoTextureSpec(); // "uGgxAlbedo"
Texture createGgxAlbedoTexture(const TextureAllocator& allocate = createTexture);

} // namespace specula::gpu
