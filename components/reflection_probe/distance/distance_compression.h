#pragma once
// The compressed form of a distance probe's layers (issue 36, `--compress bc6h`): radiance as
// BC6H blocks (engine/image/bc6h.h, 1 byte per texel), distance as a separate half float
// (2 bytes per texel; float32 where a distance does not fit a half's normal range, as
// allLayersFitHalf tells). 3 bytes per texel against 16 for RGBA32F and 8 for RGBA16F.
#include "components/reflection_probe/distance/distance_probe_asset.h"

#include <cstddef>

namespace specula {

// Replaces every layer's radiance with its BC6H encoding decoded again, and its distances with
// the texture's (half floats where every layer fits them, else unchanged): the asset as the
// compressed variant holds it, so the CPU twin measures what compression costs.
void roundTripLayersThroughBc6h(DistanceProbeAsset& asset);

// GPU bytes of one cube of `faceRes` (six faces, no mips) per texel format.
std::size_t cubeBytesRgba32f(int faceRes);
std::size_t cubeBytesRgba16f(int faceRes);
std::size_t cubeBytesBc6hR16f(int faceRes); // BC6H radiance + R16F distance

} // namespace specula
