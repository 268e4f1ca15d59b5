#include "assetcooker/lib/plan/plan_layer_packing.h"

#include <limits>

namespace specula {

LayerPacking packNearObjects(const std::vector<std::vector<std::uint32_t>>& texels,
                             std::size_t texelCount, std::size_t maxLayers) {
    LayerPacking packing;
    std::vector<std::vector<char>> occupied; // per layer, per texel
    for (std::size_t i = 0; i < texels.size(); ++i) {
        std::size_t best = occupied.size(), bestOverlap = std::numeric_limits<std::size_t>::max();
        for (std::size_t l = 0; l < occupied.size() && bestOverlap > 0; ++l) {
            std::size_t overlap = 0;
            for (const std::uint32_t t : texels[i])
                overlap += std::size_t(occupied[l][t]);
            // Below the cap only a layer it overlaps nowhere will do.
            if (overlap < bestOverlap && (overlap == 0 || occupied.size() >= maxLayers))
                best = l, bestOverlap = overlap;
        }
        if (best == occupied.size()) {
            occupied.emplace_back(texelCount, char(0));
            packing.layers.emplace_back();
        } else if (bestOverlap > 0) {
            ++packing.forced;
            packing.forcedTexels += bestOverlap;
        }
        for (const std::uint32_t t : texels[i])
            occupied[best][t] = 1;
        packing.layers[best].push_back(i);
    }
    return packing;
}

} // namespace specula
