#include "distance_glossy_chain.h"

#include "engine/core/error.h"

#include <algorithm>
#include <string>

namespace specula {

CubeChain glossyChainOf(const DistanceProbeAsset& asset, const GgxPrefilterOptions& options) {
    if (asset.layers.empty())
        throw Error(asset.manifestPath, "layers", "a glossy lookup needs the composite (layer 0)");
    const CubeFaces& composite = asset.layers[0].faces;
    if (asset.glossyLevels.empty()) {
        GgxPrefilterOptions o = options;
        o.dInf = asset.dInf;
        return prefilterGgx(composite, o);
    }
    const int n = composite[0].width;
    const int levels = int(asset.glossyLevels.size()) + 1;
    CubeChain chain;
    chain.dInf = asset.dInf;
    chain.levels.reserve(std::size_t(levels));
    chain.levels.push_back(composite);
    chain.roughness.push_back(0.f);
    for (int i = 1; i < levels; ++i) {
        const CubeFaces& faces = asset.glossyLevels[std::size_t(i - 1)];
        const int want = std::max(1, n >> std::min(i, 30));
        for (int f = 0; f < 6; ++f) {
            const Image& img = faces[std::size_t(f)];
            if (img.width != want || img.height != want || img.channels != 4 ||
                img.pixels.size() != std::size_t(want) * want * 4)
                throw Error(asset.manifestPath,
                            "glossy level " + std::to_string(i) + " face " + std::to_string(f),
                            "expected " + std::to_string(want) + "x" + std::to_string(want) +
                                " RGBA, got " + std::to_string(img.width) + "x" +
                                std::to_string(img.height) + " with " +
                                std::to_string(img.channels) + " channels");
        }
        chain.levels.push_back(faces);
        chain.roughness.push_back(ggxChainRoughness(i, levels));
    }
    return chain;
}

} // namespace specula
