#pragma once
// Synthetic PEM assets (probe/pem_runtime_test, probe/host_pem_test): sample maps of random
// texels, and a random distance geometry, so a lookup's every fetch is told apart.
#include "components/reflection_probe/pem/pem_asset.h"

#include <memory>
#include <random>

namespace specula::test {

// `count` samples at parameters 0 .. 1, evenly spaced, each map random in [0, 1).
inline PemAsset randomAsset(int faceRes, int count, glm::vec3 boxMin, glm::vec3 boxMax,
                            unsigned seed = 7) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    PemAsset a;
    a.centre = {0.25f, 1.5f, -0.5f};
    a.parameterKind = "reflector";
    a.path = "line";
    a.faceRes = faceRes;
    a.boxMin = boxMin;
    a.boxMax = boxMax;
    for (int k = 0; k < count; ++k) {
        PemSampleMap s;
        s.parameter = count > 1 ? float(k) / float(count - 1) : 0.f;
        s.map = {faceRes, boxMin, boxMax, {}, nullptr};
        for (int t = 0; t < PemMap::texelCount(faceRes); ++t)
            s.map.texels.emplace_back(u(rng), u(rng), u(rng));
        a.samples.push_back(std::move(s));
    }
    return a;
}

// Gives the asset and every sample map one distance geometry: `m`^2 faces of distances in
// [0.5, 5) m, d_inf 1000, a search of the cooker's kind.
inline void addDistanceGeometry(PemAsset& a, int m, unsigned seed = 9) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.5f, 5.f);
    auto g = std::make_shared<PemDistanceGeometry>();
    g->faceRes = m;
    for (int t = 0; t < PemMap::texelCount(m); ++t)
        g->distances.push_back(u(rng));
    g->dInf = 1000.f;
    g->range = 5.25f;
    g->tolerance = 5.25e-3f;
    g->maxSteps = 11;
    a.geometry = "distance";
    a.distance = g;
    for (PemSampleMap& s : a.samples)
        s.map.distance = g;
}

} // namespace specula::test
