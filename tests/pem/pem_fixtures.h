#pragma once
// Random maps and assets the PEM tests share (pem_local_test, pem_local_asset_test,
// pem_local_runtime_test, pem_mip_*): the same fill order everywhere, so a seed gives the
// same texels whichever test asks.
#include "components/reflection_probe/pem/pem_asset.h"
#include "components/reflection_probe/pem/pem_map_levels.h"

#include <random>

namespace specula::test {

// A local map's texels: per texel a coverage alpha, then premultiplied RGB (rgb <= alpha).
inline void fillRandomLocal(PemMap& m, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (int t = 0; t < PemMap::texelCount(m.faceRes); ++t) {
        const float alpha = u(rng);
        m.alpha.push_back(alpha);
        m.texels.emplace_back(alpha * u(rng), alpha * u(rng), alpha * u(rng));
    }
}

inline PemMap randomLocal(int n, PemLocalSphere sphere, unsigned seed) {
    PemMap m;
    m.faceRes = n;
    m.local = sphere;
    std::mt19937 rng(seed);
    fillRandomLocal(m, rng);
    return m;
}

// `header` (centre, faceRes, box, local layer, mipLevels) with `count` samples at k / count,
// each a distant map of random RGB in [0, 1) over every level and, with a local layer, a
// random local map.
inline PemAsset randomPemAsset(PemAsset header, int count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (int k = 0; k < count; ++k) {
        PemSampleMap s;
        s.parameter = float(k) / float(count);
        s.map = {header.faceRes, header.boxMin, header.boxMax, {}, header.distance};
        s.map.levels = header.mipLevels;
        for (int t = 0; t < PemMap::texelCount(header.faceRes, header.mipLevels); ++t)
            s.map.texels.emplace_back(u(rng), u(rng), u(rng));
        if (header.localLayer) {
            s.local.faceRes = header.localFaceRes;
            s.local.local = header.localSphere;
            fillRandomLocal(s.local, rng);
        }
        header.samples.push_back(std::move(s));
    }
    return header;
}

// A box-geometry asset centred at (0, 1, 0) with `levels` MIP levels of faces of `faceRes`
// (odd sizes halve as GL's levels do), `count` random samples.
inline PemAsset randomMipPemAsset(int faceRes, int levels, int count, unsigned seed) {
    PemAsset a;
    a.centre = {0.f, 1.f, 0.f};
    a.faceRes = faceRes;
    a.mipLevels = levels;
    return randomPemAsset(a, count, seed);
}

} // namespace specula::test
