// The bench's pieces that need no GPU: the Pareto front, the plot, the method table.
#include "assetcooker/lib/scene/walk_amplitude.h"
#include "sandbox/lib/bench/accuracy_plot.h"
#include "sandbox/lib/bench/bench_methods.h"
#include "sandbox/lib/walk/probe_source.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace specula;

TEST(AccuracyPlot, ParetoFrontKeepsOnlyUndominatedPointsByTime) {
    const std::vector<PlotPoint> pts = {
        {"envmap", "-", 1.0, 20.0},      // front: fastest
        {"boxproj", "-", 1.1, 19.0},     // dominated by envmap
        {"bisection", "a", 2.0, 30.0},   // front
        {"bisection", "b", 3.0, 29.0},   // dominated
        {"secant", "a", 2.5, 35.0},      // front
        {"layered", "a", 6.0, 35.0},     // dominated (same PSNR, slower)
        {"nan", "a", 1.5, std::nan("")}, // left out
    };
    const auto front = paretoFront(pts);
    ASSERT_EQ(front.size(), 3u);
    EXPECT_EQ(front[0], 0u);
    EXPECT_EQ(front[1], 2u);
    EXPECT_EQ(front[2], 4u);
}

TEST(AccuracyPlot, DrawsOnePanelPerScene) {
    PlotPanel a{"room", {{"envmap", "-", 1.0, 20.0}, {"bisection", "x", 3.0, 30.0}}};
    PlotPanel b{"empty", {}};
    const Image img = accuracyPlot({a, b}, 320, 240);
    EXPECT_EQ(img.width, 640);
    EXPECT_EQ(img.height, 240);
    double sum = 0;
    for (float v : img.pixels) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0);
}

TEST(BenchMethods, EnvmapFirstGroundTruthLastEveryToleranceSwept) {
    BenchSweep sweep;
    const auto rows = benchVariants(sweep);
    ASSERT_GE(rows.size(), 16u);
    EXPECT_EQ(rows.front().method, "envmap");
    EXPECT_EQ(rows.back().method, "groundtruth");
    EXPECT_EQ(rows.back().kind, VariantKind::GroundTruth);
    std::set<std::string> seen;
    for (const auto& r : rows)
        seen.insert(r.method + " " + r.params);
    for (const char* m : {"bisection", "secant", "march", "layered"})
        for (float de : sweep.tolerances)
            EXPECT_TRUE(seen.count(std::string(m) + " " + formatTolerance(de))) << m;
    EXPECT_TRUE(seen.count("boxproj -"));
    EXPECT_TRUE(seen.count("avgdist -"));
    // Light-field rows appear only with a cooked light field to draw.
    sweep.lightFields = {"num=8 res=16"};
    const auto withLf = benchVariants(sweep);
    EXPECT_EQ(withLf.size(), rows.size() + 1u);
    // Every flavour's methods are offered (walk --method, the plot's colours): PEM last.
    const auto methods = sandboxMethods();
    ASSERT_GE(methods.size(), 3u);
    EXPECT_STREQ(methods[methods.size() - 3].name, "lightfield");
    EXPECT_STREQ(methods[methods.size() - 2].name, "pem");
    EXPECT_STREQ(methods.back().name, "pem-nearest");
}

TEST(WalkPaths, StayInsideTheCell) {
    for (WalkPath p : {WalkPath::Orbit, WalkPath::Line, WalkPath::Figure8})
        for (int i = 0; i <= 100; ++i) {
            const glm::vec3 o = walkOffset(p, float(i) / 100.f, 0.3f);
            EXPECT_LE(std::abs(o.x), 0.3f + 1e-5f);
            EXPECT_LE(std::abs(o.y), 0.3f + 1e-5f);
            EXPECT_LE(std::abs(o.z), 0.3f + 1e-5f);
        }
    // The default room's reflectors keep inside the cell over the whole path.
    ReflectionScene room(defaultScenePath(), "");
    const float a = room.walkAmplitude();
    EXPECT_GT(a, 0.1f);
    EXPECT_LE(a, 0.2f * room.cellSize() + 1e-6f);
    const float half = 0.5f * room.cellSize();
    for (WalkPath p : {WalkPath::Orbit, WalkPath::Line, WalkPath::Figure8})
        for (int i = 0; i <= 40; ++i) {
            room.setReflectorOffset(walkOffset(p, float(i) / 40.f, a));
            for (ecs::Entity e : room.markup().mirrorEntities) {
                const Aabb b = meshWorldBounds(room.registry(), e);
                const glm::vec3 c = room.probeCentre();
                for (int k = 0; k < 3; ++k) {
                    EXPECT_GE(b.min[k] - c[k], -half - 1e-4f);
                    EXPECT_LE(b.max[k] - c[k], half + 1e-4f);
                }
            }
        }
    WalkPath w;
    EXPECT_TRUE(parseWalkPath("figure8", w));
    EXPECT_FALSE(parseWalkPath("spiral", w));
}
