#pragma once
// Synthetic light fields and random reflector configurations for the CPU glossy-filter tests.
#include "components/reflection_probe/lightfield/lightfield_asset.h"
#include "engine/image/srgb.h"
#include "lightfield_glossy_room.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <glm/glm.hpp>

namespace specula::test::lf_glossy {

inline LightFieldAsset emptyAsset(int num, int res, float cell,
                                  LightFieldCompression c = LightFieldCompression::None) {
    LightFieldAsset a;
    a.cellSize = cell;
    a.cameras = num;
    a.res = res;
    a.compression = c;
    for (auto& s : a.slabs)
        s.data.assign(a.layerBytes(), 0);
    return a;
}

inline std::uint8_t srgbCode(float linear) {
    return std::uint8_t(std::lround(255.f * linearToSrgbValue(std::clamp(linear, 0.f, 1.f))));
}

// A reflector configuration: point, normal, the mirror direction of a view with n.v >= minNv.
struct Config {
    glm::vec3 p, n, lhat, v; // v: unit, eye to surface
};
inline Config randomConfig(std::mt19937& rng, float h, float minNv) {
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    Config c;
    c.p = 0.8f * h * glm::vec3(u(rng), u(rng), u(rng));
    c.n = randomUnit(rng);
    do
        c.v = randomUnit(rng);
    while (-glm::dot(c.v, c.n) < minNv);
    c.lhat = mirrorOf(c.v, c.n);
    return c;
}

inline double maxAbs(glm::dvec3 d) {
    return std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
}

} // namespace specula::test::lf_glossy
