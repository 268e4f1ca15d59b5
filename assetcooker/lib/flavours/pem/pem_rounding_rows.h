#pragma once
// Rows for the lookups the display's rounding reaches (issue 12).
//
// The distance geometry's search reads its cube at the nearest texel: a ray whose search
// passes within rounding of a texel boundary reads one neighbour from one side and the other
// from the other side, the search goes on elsewhere and ends on other map texels. The
// display's x and l are the rasteriser's interpolants, not the tracer's hit: on the room at
// 160x120 they differ by 4e-6 m and 2e-5 rad on average (6.9e-4 rad at worst). The fit then
// holds the target where the tracer's ray reads, and the display reads a texel no row
// pinned, filled by the prior: measured there, 2 of 665 reflector pixels drew 0.32 for a
// target of 1.0 and took the display to 29.3 dB against the fit's own 56.8 dB.
//
// So each ray's lookup is repeated with x and l moved by a few times that rounding along each
// axis; wherever a moved lookup reads other texels, a copy of the ray with the moved input
// becomes a row of its own, with the ray's target: whichever side the display lands on, it
// reads a texel fitted to what the ray sees.
#include "assetcooker/lib/flavours/pem/pem_infer.h"
#include "components/reflection_probe/pem/pem_lookup_cpu.h"

namespace specula {

// A moved lookup needs a row when more than this share of its weight sits on texels other
// than the ray's (or another kept copy's): half the L1 distance of the weights.
inline constexpr float kPemRoundingShift = 0.25f;

// reach: each coordinate of x moves by this many metres both ways, and each of l by this
// much before l is normalised again (radians, near enough).
// The copies to append to `samples` (in sample order, then move order; each a row of its own:
// pixel -1, no footprint partners beyond the ray's own): one per moved lookup whose weights
// shift by more than kPemRoundingShift from the ray's and from every copy kept before it.
// Deterministic: the same samples give the same copies whatever the threads.
PemSamples pemRoundingCopies(const PemLookupCpu& lookup, const PemSamples& samples, float reach);

} // namespace specula
