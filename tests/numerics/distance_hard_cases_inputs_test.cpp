// Hard cases for the distance-cubemap flavour, on the inputs: d_e -> 0, a range D
// too small or too large for the scene, zero and NaN normals, world coordinates around 1e5 m,
// half-float distances (the geometry: distance_hard_cases_test.cpp). Every case runs the C++
// twin and the GLSL lookup (the same shared code, on the GPU through GpuLookup) over the same
// rays and asserts, per method: every output is finite, and its worst error against the closed
// form is below the bound the case states. Each measured worst error is printed as one
// "[numerics]" line.
#include "distance_hard_cases_fixture.h"
#include "numerics_common.h"

#include <glm/gtc/packing.hpp>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

namespace specula::glsl {
namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include "components/reflection_probe/shaders/reflector_common.glsl.h"
#pragma GCC diagnostic pop
} // namespace
} // namespace specula::glsl

using namespace specula;
using namespace specula::test;
using namespace specula::test::hard_cases;

// ---------------------------------------------------------------------------------------
// d_e -> 0, D smaller than the scene (no bracket), D absurdly large.

TEST(DistanceHardCases, ToleranceToZero) {
    std::mt19937 rng(17);
    std::vector<Ray> rays;
    for (int i = 0; i < 3000; ++i)
        rays.push_back({randomInCell(rng), randomUnit(rng)});
    for (float de : {0.f, FLT_MIN, 1e-40f, -1.f, kNaN, kInf}) {
        const DistanceLookupConfig c = configFor(boxProbe(), DistanceMethod::Bisection, de);
        EXPECT_GT(c.params.tolerance, 0.f);
        EXPECT_TRUE(std::isfinite(c.params.tolerance));
        EXPECT_LE(c.params.maxSteps, 40) << "N is capped so d_e -> 0 cannot loop for long";
        char name[64];
        std::snprintf(name, sizeof name, "d_e -> 0 (d_e = %g)", double(de));
        checkCase(name, boxProbe(), rays, boxIdeal(boxProbe()),
                  {{DistanceMethod::Bisection, 0.2},
                   {DistanceMethod::Secant, 0.2},
                   {DistanceMethod::March, 0.2},
                   {DistanceMethod::Layered, 0.2}},
                  de);
    }
}

TEST(DistanceHardCases, RangeSmallerThanTheScene) {
    // With D below the scene's extent the bracket (x, x + 2D) misses the walls: the search
    // cannot find the surface. The answer must still be finite and a colour the probe holds
    // (within 0.8 sqrt(3) = 1.39 of any other); envmap runs alongside for comparison. Finding:
    // without a bracket the search does worse than envmap; D must come from the bake.
    std::mt19937 rng(19);
    std::vector<Ray> rays;
    for (int i = 0; i < 3000; ++i)
        rays.push_back({randomInCell(rng), randomUnit(rng)});
    const Reference exact = [](DistanceMethod, glm::vec3 x, glm::vec3 d) {
        return room().trace(x, d);
    };
    for (float D : {0.5f, 0.05f, 1e-6f}) {
        char name[64];
        std::snprintf(name, sizeof name, "D smaller than scene (D = %g)", double(D));
        checkCase(name, boxProbe(), rays, exact,
                  {{DistanceMethod::Envmap, 1.39},
                   {DistanceMethod::Bisection, 1.39},
                   {DistanceMethod::Secant, 1.39},
                   {DistanceMethod::March, 1.39},
                   {DistanceMethod::Layered, 1.39}},
                  0.01f, D);
    }
}

TEST(DistanceHardCases, RangeFarLargerThanTheScene) {
    // D = 1e30: |l| overflows float on the first step. Finite output, and with N capped at
    // 40 the search ends far from the wall: only finiteness and the stored range hold.
    std::mt19937 rng(23);
    std::vector<Ray> rays;
    for (int i = 0; i < 1000; ++i)
        rays.push_back({randomInCell(rng), randomUnit(rng)});
    const Reference exact = [](DistanceMethod, glm::vec3 x, glm::vec3 d) {
        return room().trace(x, d);
    };
    // Up to 1e4 (10x d_inf) the 40 steps still reach the wall; from ~1e7 on, x is lost in
    // x + D l-hat (ulp(1e7) = 1 m) and only finiteness and the colour range hold.
    for (float D : {1e4f, 1e7f, 1e30f, FLT_MAX}) {
        const double bound = D <= 1e4f ? 0.05 : 1.39;
        char name[64];
        std::snprintf(name, sizeof name, "D far larger than scene (D=%g)", double(D));
        checkCase(name, boxProbe(), rays, exact,
                  {{DistanceMethod::Bisection, bound},
                   {DistanceMethod::Secant, bound},
                   {DistanceMethod::March, bound},
                   {DistanceMethod::Layered, bound}},
                  0.01f, D);
    }
}

// ---------------------------------------------------------------------------------------
// Zero and NaN normals (assets): the reflector shader's safeNormal + mirrorDirection.

TEST(DistanceHardCases, ZeroAndNanNormals) {
    std::mt19937 rng(31);
    const std::vector<glm::vec3> badNormals = {glm::vec3(0.f),
                                               glm::vec3(kNaN),
                                               glm::vec3(kNaN, 0.f, 1.f),
                                               glm::vec3(kInf, 0.f, 0.f),
                                               glm::vec3(-kInf, kInf, 0.f),
                                               glm::vec3(1e-40f, 0.f, 0.f),
                                               glm::vec3(1e-12f, 0.f, 1e-12f),
                                               glm::vec3(1e20f, 1e20f, 0.f)};
    std::vector<GpuRay> gr;
    std::vector<glm::vec3> wantDir;
    double worstDir = 0.0;
    for (int i = 0; i < 400; ++i) {
        const glm::vec3 v = randomUnit(rng);
        const glm::vec3 g = randomUnit(rng);
        const glm::vec3 n = badNormals[std::size_t(i) % badNormals.size()];
        // Expected: the mirror about the geometric normal, computed in double.
        const glm::dvec3 gd(g), vd(v);
        const glm::dvec3 nf = glm::dot(gd, vd) > 0.0 ? -gd : gd;
        const glm::vec3 want(glm::normalize(vd - 2.0 * glm::dot(vd, nf) * nf));
        const glm::vec3 got = glm::normalize(glsl::mirrorDirection(v, glsl::safeNormal(n, g)));
        ASSERT_TRUE(finite3(got));
        worstDir = std::max(worstDir, double(glm::length(got - want)));
        gr.push_back({randomInCell(rng), v, n, g});
        wantDir.push_back(want);
    }
    std::printf("[numerics] %-34s C++ reflected direction worst %.3e (bound 1e-5)\n",
                "zero/NaN/inf normals", worstDir);
    EXPECT_LT(worstDir, 1e-5);
    // Through the shader: the reflected direction it used and the radiance.
    for (DistanceMethod m : {DistanceMethod::Bisection, DistanceMethod::BoxProj}) {
        const DistanceLookupConfig cfg = configFor(boxProbe(), m);
        CpuDistanceProbe twin(boxProbe(), cfg);
        const auto out = gpuLookup().run(boxProbe(), cfg, gr, 1);
        Worst dir, rad, cpu;
        for (std::size_t i = 0; i < out.size(); ++i) {
            dir.add(out[i].lhat, wantDir[i]);
            const glm::vec3 ref = room().trace(gr[i].x, wantDir[i]);
            rad.add(out[i].radiance, ref);
            int f = 0;
            cpu.add(twin.radiance(gr[i].x, wantDir[i], f), ref);
        }
        report("zero/NaN/inf normals (direction)", toString(m), "glsl", dir, 1e-5);
        report("zero/NaN/inf normals (radiance)", toString(m), "glsl", rad, 0.1);
        report("zero/NaN/inf normals (radiance)", toString(m), "cpu", cpu, 0.1);
        EXPECT_EQ(dir.nonFinite + rad.nonFinite + cpu.nonFinite, 0);
        EXPECT_LT(dir.err, 1e-5);
        EXPECT_LT(rad.err, 0.1);
        EXPECT_LT(cpu.err, 0.1);
    }
    // Geometric normal NaN as well (a sliver triangle): l-hat is NaN; the lookup must still
    // give a finite colour that the probe holds.
    std::vector<GpuRay> nanAll(
        64, GpuRay{glm::vec3(0.1f), glm::vec3(0.f, 0.f, -1.f), glm::vec3(kNaN), glm::vec3(kNaN)});
    for (DistanceMethod m : kAllMethods) {
        const DistanceProbeAsset a =
            m == DistanceMethod::Layered ? withObjectLayer(boxProbe(), "bisection") : boxProbe();
        const DistanceLookupConfig cfg = configFor(a, m);
        CpuDistanceProbe twin(a, cfg);
        int f = 0;
        const glm::vec3 c = twin.radiance(glm::vec3(0.1f), glm::vec3(kNaN), f);
        EXPECT_TRUE(finite3(c)) << toString(m);
        const auto out = gpuLookup().run(a, cfg, nanAll, 1);
        for (const GpuResult& r : out)
            EXPECT_TRUE(finite3(r.radiance)) << toString(m);
    }
}

// ---------------------------------------------------------------------------------------
// World coordinates around 1e5 m: float cancellation in world - centre and world - eye.

TEST(DistanceHardCases, HugeWorldCoordinates) {
    for (double far : {1e3, 1e5, 1e6}) {
        const glm::dvec3 centre(far, 0.37 * far, -far);
        std::mt19937 rng(37);
        std::vector<GpuRay> gr;
        std::vector<glm::vec3> xs, ds, want;
        for (int i = 0; i < 2000; ++i) {
            const glm::vec3 xLocal = randomInCell(rng);
            const glm::vec3 world = glm::vec3(centre + glm::dvec3(xLocal)); // as stored
            const glm::vec3 eye = glm::vec3(centre + glm::dvec3(0.3, 0.9, 3.5));
            const glm::vec3 g = randomUnit(rng);
            // Exact: probe-local position and view ray from the stored floats, in double.
            const glm::dvec3 xd = glm::dvec3(world) - centre;
            const glm::dvec3 vd = glm::normalize(glm::dvec3(world) - glm::dvec3(eye));
            const glm::dvec3 gd(g);
            const glm::dvec3 nf = glm::dot(gd, vd) > 0.0 ? -gd : gd;
            const glm::vec3 dExact(glm::normalize(vd - 2.0 * glm::dot(vd, nf) * nf));
            want.push_back(room().trace(glm::vec3(xd), dExact));
            // As the shader does it, in float.
            const glm::vec3 x = world - glm::vec3(centre);
            const glm::vec3 v = glm::normalize(world - eye);
            xs.push_back(x);
            ds.push_back(glm::normalize(glsl::mirrorDirection(v, glsl::safeNormal(g, g))));
            gr.push_back({world, eye, g, g});
        }
        const double bound = far <= 1e5 ? 0.1 : 1.0;
        for (DistanceMethod m : {DistanceMethod::BoxProj, DistanceMethod::Bisection}) {
            const DistanceLookupConfig cfg = configFor(boxProbe(), m);
            CpuDistanceProbe twin(boxProbe(), cfg);
            Worst cpu, gpu;
            for (std::size_t i = 0; i < xs.size(); ++i) {
                int f = 0;
                cpu.add(twin.radiance(xs[i], ds[i], f), want[i]);
            }
            const auto out = gpuLookup().run(boxProbe(), cfg, gr, 2, glm::vec3(centre));
            for (std::size_t i = 0; i < out.size(); ++i)
                gpu.add(out[i].radiance, want[i]);
            char name[64];
            std::snprintf(name, sizeof name, "world coordinates ~%g m", far);
            report(name, toString(m), "cpu", cpu, bound);
            report(name, toString(m), "glsl", gpu, bound);
            EXPECT_EQ(cpu.nonFinite + gpu.nonFinite, 0);
            EXPECT_LE(cpu.err, bound) << name;
            EXPECT_LE(gpu.err, bound) << name;
        }
    }
}

// ---------------------------------------------------------------------------------------
// Half-float distance storage: what it costs against float.

TEST(DistanceHardCases, HalfFloatDistanceStorage) {
    DistanceProbeAsset half = boxProbe();
    double worstStore = 0.0;
    for (auto& face : half.layers[0].faces)
        for (int y = 0; y < face.height; ++y)
            for (int x = 0; x < face.width; ++x) {
                float& d = face.at(x, y)[3];
                const float h = glm::unpackHalf1x16(glm::packHalf1x16(d));
                worstStore = std::max(worstStore, double(std::abs(h - d)));
                d = h;
            }
    std::printf("[numerics] %-34s worst stored distance error %.3e m (half ulp at 4 m: %.3e)\n",
                "half-float distances", worstStore, 4.0 / 2048.0);
    std::mt19937 rng(41);
    std::vector<Ray> rays;
    for (int i = 0; i < 20000; ++i)
        rays.push_back({randomInCell(rng), randomUnit(rng)});
    const Reference exact = [](DistanceMethod, glm::vec3 x, glm::vec3 d) {
        return room().trace(x, d);
    };
    for (float de : {0.01f, 0.001f})
        for (DistanceMethod m :
             {DistanceMethod::Bisection, DistanceMethod::Secant, DistanceMethod::March}) {
            Worst w[2];
            for (int k = 0; k < 2; ++k) {
                const DistanceProbeAsset& a = k == 0 ? boxProbe() : half;
                CpuDistanceProbe twin(a, configFor(a, m, de));
                for (const Ray& r : rays) {
                    int f = 0;
                    w[k].add(twin.radiance(r.x, r.d, f), exact(m, r.x, r.d));
                }
            }
            std::printf("[numerics] %-34s %-9s d_e=%-5g float: worst %.3e rms %.3e | half: "
                        "worst %.3e rms %.3e | cost: rms x%.3f\n",
                        "half vs float distances", toString(m), double(de), w[0].err, w[0].rms(),
                        w[1].err, w[1].rms(), w[1].rms() / w[0].rms());
            EXPECT_EQ(w[1].nonFinite, 0);
            // Half stores 4 m to 2 mm: its RMS may grow by at most 25 % over float, and its
            // worst error by at most 0.05.
            EXPECT_LE(w[1].rms(), 1.25 * w[0].rms() + 1e-4);
            EXPECT_LE(w[1].err, w[0].err + 0.05);
        }
    // The shader on half data (as an RGBA16F texture would hold it).
    std::vector<Ray> few(rays.begin(), rays.begin() + 3000);
    checkCase("half-float distances", half, few, boxIdeal(half),
              {{DistanceMethod::Bisection, 0.2}, {DistanceMethod::Secant, 0.2}});
}
