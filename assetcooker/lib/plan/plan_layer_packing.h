#pragma once
// Near objects packed into a bounded number of object layers. A level of clutter holds
// thousands of near objects; one layer each would exceed what the runtime binds
// (glsl::kMaxDistanceLayers - 1 object layers) and cost a cube map per node. Objects whose
// coverage from the reflectors' cell (their grown texel masks) never meets can share a layer
// without losing any occlusion: no reflected ray sees one behind the other. So each object,
// near to far, joins the first layer it overlaps nowhere; past the cap, the layer it
// overlaps least (there, occlusion between those two is resolved from the probe centre only).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace specula {

struct LayerPacking {
    // Each layer's members as indices into the input, near to far; layers ordered by their
    // nearest member.
    std::vector<std::vector<std::size_t>> layers;
    // Objects that joined a layer they overlap (the cap was reached), and the texels where
    // they overlap it.
    std::size_t forced = 0;
    std::size_t forcedTexels = 0;
};

// `texels[i]`: object i's covered texels (indices below texelCount), objects near to far.
LayerPacking packNearObjects(const std::vector<std::vector<std::uint32_t>>& texels,
                             std::size_t texelCount, std::size_t maxLayers);

} // namespace specula
