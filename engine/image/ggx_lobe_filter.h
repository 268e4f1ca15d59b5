#pragma once
// The GGX lobe filter of engine/image/ggx_prefilter.h (see there for what it computes): the
// glossy levels' radiance from the input's box-filtered mips. Split out for its inner loop,
// which is where the prefilter spends its time: per level, the lobe's samples once (tangent
// space direction, n.l weight, the FIS level's constant part); per texel, one vectorised pass
// that lands every sample on a face (the repo's cubeFaceUv, bit for bit), then the trilinear
// fetches from mips padded by a texel of their neighbours (one 4-float load a tap, no seams).
#include "engine/image/ggx_prefilter.h"

#include <vector>

#include <glm/vec4.hpp>

namespace specula::ggx_filter {

// Texel (x, y) of `face`, where x or y may lie one texel past the face: such a tap reads the
// texel of the neighbouring face through the tap's direction (the face's plane extended).
// Past a corner (both out) there is no texel: the mean of the three texels at the corner.
glm::vec4 texelAcross(const CubeFaces& faces, int face, int x, int y);

// Levels 1 .. options.levels - 1 of the chain: RGB the GGX-filtered radiance, A = 0. mips[0]
// is the input (n x n), mips[i] its box-filtered mip i, down to 1 x 1. Parallel over faces x
// rows (oneTBB); the same result every run.
std::vector<CubeFaces> filterGgxLevels(const std::vector<CubeFaces>& mips,
                                       const GgxPrefilterOptions& options);

} // namespace specula::ggx_filter
