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

// Whether the composite's distances can be stored as half floats for a lookup of tolerance
// `tolerance` (d_e, metres): each a normal half (at least 2^-14), d_inf exactly a half (the
// sentinel must survive), and a half's step at the farthest hit, 2^(floor(log2 d_max) - 10),
// at most d_e. Measured (CHANGELOG.md "Storage formats"): zdm2's composite reaches 43 m, where a
// half's step is 3.1 cm against d_e = 1 cm, and half distances cost its secant lookup
// 0.16 dB; on the room, gallery and living room (step <= 0.8 cm) at most 0.003 dB.
bool compositeDistanceFitsHalf(const DistanceProbeAsset& asset, float tolerance);

// The d_e a cooked probe is meant to be looked up with: its measured plan's
// (effect_plan.lookup.tolerance) when it has one, else the component's default.
float cookedLookupTolerance(const DistanceProbeAsset& asset);

// Stores the composite as `--compress bc6h` does (DistanceCompression::Bc6h): its radiance
// encoded to compositeBlocks and replaced by their decoding, its distances rounded to half
// floats where compositeDistanceFitsHalf(cookedLookupTolerance) holds, the glossy levels'
// radiance likewise (glossyBlocks; their distances rounded with the composite's), and layer
// 0's figures
// (nearest and farthest hit, solid angle) restated from what is stored, as the reader
// measures them. An asset already compressed is left as it is.
void compressComposite(DistanceProbeAsset& asset);

// GPU bytes of one cube of `faceRes` (six faces, no mips) per texel format.
std::size_t cubeBytesRgba32f(int faceRes);
std::size_t cubeBytesRgba16f(int faceRes);
std::size_t cubeBytesBc6hR16f(int faceRes); // BC6H radiance + R16F distance
// The composite's bytes as `asset` stores it (RGBA32F, or BC6H plus R16F or R32F distance).
std::size_t compositeBytes(const DistanceProbeAsset& asset);

} // namespace specula
