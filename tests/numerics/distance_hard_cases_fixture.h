#pragma once
// The rays, probes and twin-plus-shader check shared by the distance hard-case tests.
#include "numerics_common.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace specula::test::hard_cases {

inline constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
inline constexpr float kInf = std::numeric_limits<float>::infinity();
inline constexpr float kCell = 0.7f; // reflectors move within |x_i| <= kCell of the probe centre

struct Ray {
    glm::vec3 x, d;
};
using Reference = std::function<glm::vec3(DistanceMethod, glm::vec3 x, glm::vec3 d)>;
using Bounds = std::map<DistanceMethod, double>;

inline const DistanceProbeAsset& boxProbe() {
    static const DistanceProbeAsset a = makeBoxProbe(room(), 256);
    return a;
}

inline Reference boxIdeal(const DistanceProbeAsset& a) {
    const float avg = a.layers[0].avgDistance;
    return [avg](DistanceMethod m, glm::vec3 x, glm::vec3 d) {
        return idealBox(room(), m, avg, x, d);
    };
}

// Runs `rays` through twin and shader for every method in `bounds` and checks both.
inline void checkCase(const std::string& name, const DistanceProbeAsset& asset,
                      const std::vector<Ray>& rays, const Reference& ref, const Bounds& bounds,
                      float de = 0.01f, float range = 0.f) {
    for (const auto& [m, bound] : bounds) {
        const DistanceProbeAsset layered = m == DistanceMethod::Layered
                                               ? withObjectLayer(asset, "bisection")
                                               : DistanceProbeAsset{};
        const DistanceProbeAsset& a = m == DistanceMethod::Layered ? layered : asset;
        const DistanceLookupConfig cfg = configFor(a, m, de, range);
        CpuDistanceProbe twin(a, cfg);
        Worst cpu, gpu;
        std::vector<GpuRay> gr;
        std::vector<glm::vec3> want;
        for (const Ray& r : rays) {
            int fetches = 0;
            want.push_back(ref(m, r.x, r.d));
            cpu.add(twin.radiance(r.x, r.d, fetches), want.back());
            // The search may not spend more than N fetches per layer (the march: its steps and
            // refinements), plus radiance and sky.
            EXPECT_LE(fetches,
                      (searchFetchCap(m, cfg) + 1) * std::max(1, cfg.params.layerCount) + 1)
                << name << " " << toString(m);
            gr.push_back({r.x, r.d});
        }
        const auto out = gpuLookup().run(a, cfg, gr);
        for (std::size_t i = 0; i < out.size(); ++i)
            gpu.add(out[i].radiance, want[i]);
        report(name, toString(m), "cpu", cpu, bound);
        report(name, toString(m), "glsl", gpu, bound);
        EXPECT_EQ(cpu.nonFinite, 0) << name << " " << toString(m);
        EXPECT_EQ(gpu.nonFinite, 0) << name << " " << toString(m);
        EXPECT_LE(cpu.err, bound) << name << " " << toString(m) << " (C++ twin)";
        EXPECT_LE(gpu.err, bound) << name << " " << toString(m) << " (GLSL)";
    }
}

inline glm::vec3 randomUnit(std::mt19937& rng) {
    std::normal_distribution<float> g;
    glm::vec3 d;
    do
        d = glm::vec3(g(rng), g(rng), g(rng));
    while (glm::dot(d, d) < 1e-6f);
    return glm::normalize(d);
}

inline glm::vec3 randomInCell(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-kCell, kCell);
    return glm::vec3(u(rng), u(rng), u(rng));
}

} // namespace specula::test::hard_cases
