#pragma once
// A small light-field probe made in code (NUM 2, RES 4: an 8 x 8 atlas per slab, a gradient
// per slab so BC1 has real blocks), the same bytes every time: the bad-input tests tamper
// with it and the light-field fuzz target parses manifests beside it.
#include "components/reflection_probe/lightfield/lightfield_asset.h"

#include <cstdint>
#include <vector>

namespace specula::test {

inline LightFieldAsset smallLightField(LightFieldCompression c) {
    LightFieldAsset a;
    a.cellCentre = glm::vec3(0.5f, 1.f, -2.f);
    a.cellSize = 1.f;
    a.cameras = 2;
    a.res = 4;
    a.compression = c;
    const int n = a.atlasSize();
    for (int k = 0; k < 6; ++k) {
        LightFieldSlab& s = a.slabs[std::size_t(k)];
        s.nearDepth = 1.f;
        s.farDepth = 3.f;
        s.focalDepth = 1.5f; // harmonic mean of 1 and 3
        s.minDepth = 0.5f;
        s.maxDepth = 4.f;
        s.skyFraction = 0.1f;
        s.intrudingFraction = 0.05f;
        s.disparity = disparityForDepth(a, s.focalDepth);
        std::vector<std::uint8_t> rgb(std::size_t(n) * std::size_t(n) * 3);
        for (std::size_t i = 0; i < rgb.size(); ++i)
            rgb[i] = std::uint8_t((i * 7 + std::size_t(k) * 40) % 256);
        s.data = c == LightFieldCompression::BC1 ? encodeBC1(rgb.data(), n, n) : rgb;
    }
    a.intrusions.push_back({"pillar", "slab -Y", 0.25f});
    return a;
}

} // namespace specula::test
