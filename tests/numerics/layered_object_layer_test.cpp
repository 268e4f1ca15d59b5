// Object layers of the layered lookup in closed form (issue 15, item 3), on the CPU twin and
// the shader through the same rays:
//   - the average-distance correction on an object layer off the probe centre, seen from
//     reflector points off the centre: it must find the object where the ray clearly meets
//     it (Wang et al.'s x + d-bar l-hat can lie outside the object's box and read d_inf there,
//     and the object vanished from the reflection: measured on these rays, it sees the
//     sphere on 89.9 % of them, the point on the box span on 97.9 %);
//   - a torus lying flat below the view: along a ray through its near tube, the hole and its
//     far tube, f = stored distance - |l| crosses zero more than once inside the layer's box.
#include "numerics_common.h"
#include "support/lookup_config.h"

#include <random>

using namespace specula;
using namespace specula::test;

namespace {

std::mt19937& rng() {
    static std::mt19937 g(20261203);
    return g;
}

float uniform(float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng());
}

// A reflector point in a 1.2 m cell about the probe centre.
glm::vec3 randomInCell() {
    return {uniform(-0.6f, 0.6f), uniform(-0.6f, 0.6f), uniform(-0.6f, 0.6f)};
}

glm::vec3 randomInBall(float r) {
    for (;;) {
        const glm::vec3 p(uniform(-1.f, 1.f), uniform(-1.f, 1.f), uniform(-1.f, 1.f));
        if (glm::dot(p, p) <= 1.f) return r * p;
    }
}

// Layered mode with the object layer's cooked method (the manifest's "method").
DistanceLookupConfig cookedLayered(const DistanceProbeAsset& a, float de = 0.01f) {
    return test::lookupConfigOf(a, DistanceMethod::Layered, de); // the layers' cooked methods
}

// The shader against the twin on the same rays: hit or sky alike and the radiance within
// filtering precision (2e-3, the twin agreement tests' bound) on all but 0.5 % of the rays
// (a nearest distance fetch on a texel boundary may flip on the last bit of a float).
void expectShaderMatchesTwin(const DistanceProbeAsset& a, const DistanceLookupConfig& c,
                             const std::vector<GpuRay>& rays, const std::string& what) {
    const std::vector<GpuResult> gpu = gpuLookup().run(a, c, rays);
    const CpuDistanceProbe twin(a, c);
    long sameHit = 0, close = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const CpuDistanceProbe::CompositeHit h = twin.lookupHit(rays[i].x, rays[i].a);
        const float e = glm::length(gpu[i].radiance - h.radiance);
        if (gpu[i].sky != !h.hit) continue;
        ++sameHit;
        if (e < 2e-3f) ++close;
    }
    const double n = double(rays.size());
    std::printf("[numerics] %-36s shader vs twin over %zu rays: same hit %.2f %%, radiance within "
                "2e-3 %.2f %%\n",
                what.c_str(), rays.size(), 100.0 * double(sameHit) / n, 100.0 * double(close) / n);
    EXPECT_GT(double(sameHit) / n, 0.995) << what;
    EXPECT_GT(double(close) / n, 0.995) << what;
}

// A torus lying flat (axis +y), closed form through its signed distance: sphere tracing
// from x along unit d finds the first surface point exactly (each step is at most the
// distance to the surface), to 1e-6 m.
struct FlatTorus {
    glm::vec3 c{0.f, -1.2f, -2.5f}; // seen from the centre 25 degrees down: the hole opens
    float major = 1.f, minor = 0.3f;
    float sdf(glm::vec3 p) const {
        const glm::vec3 q = p - c;
        return glm::length(glm::vec2(std::sqrt(q.x * q.x + q.z * q.z) - major, q.y)) - minor;
    }
    std::optional<float> hit(glm::vec3 x, glm::vec3 d, float tMax = 20.f) const {
        float t = 0.f;
        for (int i = 0; i < 4000 && t < tMax; ++i) {
            const float s = sdf(x + t * d);
            if (s < 1e-6f) return t;
            t += s;
        }
        return std::nullopt;
    }
    glm::vec3 lo() const { return c - glm::vec3(major + minor, minor, major + minor); }
    glm::vec3 hi() const { return c + glm::vec3(major + minor, minor, major + minor); }
};

} // namespace

TEST(LayeredObjectLayer, AverageDistanceFindsAnOffCentreObject) {
    // A 0.25 m sphere 2.5 m from the centre; its d-bar is about 2.3 m. From a reflector point
    // up to 0.6 m off the centre the ray meets it anywhere from 1.7 to 3.1 m along, so x +
    // d-bar l-hat may miss the sphere's 0.5 m box.
    Sphere s;
    s.c = glm::vec3(0.3f, 0.2f, -2.5f);
    s.r = 0.25f;
    const DistanceProbeAsset a = withObjectLayer(makeSphereProbe(128, s), "avgdist");
    const DistanceLookupConfig c = cookedLayered(a);
    ASSERT_EQ(c.layers[1].method, info(DistanceMethod::AvgDist).glslIndex);
    const CpuDistanceProbe twin(a, c);
    std::vector<GpuRay> rays;
    long clear = 0, found = 0, wang = 0;
    double tError = 0.0;
    const float avg = a.layers[1].avgDistance;
    while (rays.size() < 4000) {
        const glm::vec3 x = randomInCell();
        const glm::vec3 d = glm::normalize(s.c + randomInBall(s.r) - x);
        const auto t = s.hit(x, d);
        // Clearly inside the outline: a silhouette texel cannot decide the ray.
        if (!t || s.margin(x, d) > -0.1f * s.r) continue;
        rays.push_back({x, d});
        const CpuDistanceProbe::CompositeHit h = twin.lookupHit(x, d);
        ++clear;
        // Wang et al.'s point x + d-bar l-hat: the fetch there sees the sphere iff the
        // direction from the centre meets it.
        wang += s.hit(glm::vec3(0.f), glm::normalize(x + avg * d)).has_value();
        if (!h.hit) continue;
        ++found;
        tError += std::abs(h.t - *t);
    }
    const double share = double(found) / double(clear);
    std::printf("[numerics] avgdist object layer off the centre: found on %.2f %% of %ld rays "
                "that clearly meet it (x + d-bar l-hat would see it on %.2f %%), mean |t - "
                "t_true| %.3f m (radius %.2f m)\n",
                100.0 * share, clear, 100.0 * double(wang) / double(clear),
                found ? tError / double(found) : 0.0, double(s.r));
    EXPECT_GT(share, 0.95);
    // The hit is a point of the sphere seen from the centre, projected onto the ray.
    EXPECT_LT(tError / double(std::max(found, 1L)), double(s.r));
    expectShaderMatchesTwin(a, c, rays, "avgdist object layer off the centre");
}

TEST(LayeredObjectLayer, TorusWhoseDistanceCrossesZeroMoreThanOnce) {
    const FlatTorus torus;
    auto seen = [&](glm::vec3 dir) { return torus.hit(glm::vec3(0.f), dir); };
    const DistanceProbeAsset a = makeProbe(
        128, 1000.f,
        [&](glm::vec3 d, glm::vec3& rgb, float& t) {
            const auto h = seen(d);
            rgb = h ? AnalyticBox::radianceAt(*h * d) : glm::vec3(0.f);
            t = h ? *h : -1.f;
        },
        torus.lo(), torus.hi());
    // Rays from the cell to points of the torus's band, kept where the closed-form f (the
    // centre's distance in the direction of l less |l|) changes sign more than once along
    // the ray and the centre sees the first hit (else no lookup of this probe can find it).
    std::vector<GpuRay> rays;
    std::vector<float> first;
    while (rays.size() < 2000) {
        const glm::vec3 x = randomInCell();
        const glm::vec3 target =
            torus.c + glm::vec3(uniform(-1.f, 1.f) * (torus.major + torus.minor),
                                uniform(-0.8f, 0.8f) * torus.minor, uniform(-1.f, 1.f));
        const glm::vec3 d = glm::normalize(target - x);
        const auto t = torus.hit(x, d);
        if (!t) continue;
        const glm::vec3 q = x + *t * d;
        const auto back = seen(glm::normalize(q));
        if (!back || std::abs(*back - glm::length(q)) > 1e-3f) continue;
        int changes = 0;
        bool positive = true;
        for (int k = 1; k <= 2000; ++k) {
            const glm::vec3 l = x + 8.f * float(k) / 2000.f * d;
            const auto s = seen(glm::normalize(l));
            const bool p = !s || *s > glm::length(l);
            changes += p != positive;
            positive = p;
        }
        if (changes < 2) continue;
        rays.push_back({x, d});
        first.push_back(*t);
    }
    const float tol = 5.f * 0.01f; // 5 d_e
    for (const char* method : {"bisection", "secant", "march", "avgdist"}) {
        const DistanceProbeAsset layered = withObjectLayer(a, method);
        const DistanceLookupConfig c = cookedLayered(layered);
        const CpuDistanceProbe twin(layered, c);
        long right = 0, later = 0, fetches = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            const CpuDistanceProbe::CompositeHit h = twin.lookupHit(rays[i].x, rays[i].a);
            fetches += h.fetches;
            if (!h.hit) continue;
            if (std::abs(h.t - first[i]) <= tol) ++right;
            if (h.t > first[i] + tol) ++later;
        }
        const double n = double(rays.size());
        std::printf("[numerics] torus object layer, %-9s first crossing on %.2f %%, a later one "
                    "on %.2f %% of %zu rays; %.2f fetches a ray\n",
                    method, 100.0 * double(right) / n, 100.0 * double(later) / n, rays.size(),
                    double(fetches) / n);
        expectShaderMatchesTwin(layered, c, rays, std::string("torus, ") + method);
        // The march brackets the first crossing; bisection and secant search the box span
        // from its middle (measured 79 % first crossings, 12 % a later one: the middle of the
        // span often lies in the hole, where the layer holds d_inf and the search moves on to
        // the far tube). Bracketing them too (lookupFirstCrossing on object layers) was
        // measured a net loss on the bundled scenes, 256^2 faces, bisection on every layer:
        // room 37.00 -> 35.96 dB, bowl_room 36.42 -> 35.74, truck_room 29.12 -> 24.18 (secant
        // +0.1 to +0.3 dB at up to 61 % more fetches), so only the march is held to it here.
        if (std::string(method) == "march") {
            EXPECT_GT(double(right) / n, 0.95);
        }
    }
}
