// The bounds type against closed forms: empty-box identities, rotated cubes, distances.
#include "engine/math/aabb.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

using namespace specula;

namespace {

void expectVecNear(glm::vec3 a, glm::vec3 b, float tol) {
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(a[k], b[k], tol) << "axis " << k;
}

const Aabb kBox{{-1.f, 0.f, 2.f}, {3.f, 4.f, 6.f}};

} // namespace

TEST(Aabb, DefaultIsEmptyAndExtendingByAnEmptyBoxChangesNothing) {
    const Aabb none;
    EXPECT_TRUE(none.empty());
    EXPECT_FALSE(none.contains(glm::vec3(0.f)));
    EXPECT_FALSE(none.overlaps(kBox));
    EXPECT_FALSE(kBox.overlaps(none));
    EXPECT_TRUE(none.transformed(glm::mat4(1.f)).empty());
    EXPECT_TRUE(none.translated(glm::vec3(1.f)).empty());
    EXPECT_TRUE(Aabb::of({}).empty());
    // Nothing sticks out of a cell, and the centre of nothing is still a finite point.
    EXPECT_LT(none.overhang(Aabb::cube(glm::vec3(0.f), 1.f)), 0.f);
    for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(std::isfinite(none.centre()[k]));

    Aabb grown = kBox;
    grown.extend(none);
    EXPECT_EQ(grown.min, kBox.min);
    EXPECT_EQ(grown.max, kBox.max);
    Aabb fromNone;
    fromNone.extend(kBox);
    EXPECT_EQ(fromNone.min, kBox.min);
    EXPECT_EQ(fromNone.max, kBox.max);
}

TEST(Aabb, OnePointIsADegenerateBoxThatHoldsIt) {
    Aabb b;
    b.extend(glm::vec3(1.f, -2.f, 3.f));
    EXPECT_FALSE(b.empty());
    EXPECT_TRUE(b.contains(glm::vec3(1.f, -2.f, 3.f)));
    EXPECT_EQ(b.extent(), glm::vec3(0.f));
    EXPECT_EQ(b.boundingRadius(), 0.f);
}

TEST(Aabb, OfPointsIsTheirPerAxisMinimumAndMaximum) {
    const std::vector<glm::vec3> pts = {{3, 0, 2}, {-1, 4, 6}, {0, 1, 3}};
    const Aabb b = Aabb::of(pts);
    EXPECT_EQ(b.min, kBox.min);
    EXPECT_EQ(b.max, kBox.max);
    // Order does not matter.
    const std::vector<glm::vec3> reversed(pts.rbegin(), pts.rend());
    EXPECT_EQ(Aabb::of(reversed).min, b.min);
    EXPECT_EQ(Aabb::of(reversed).max, b.max);
}

TEST(Aabb, CentreExtentAndRadius) {
    EXPECT_EQ(kBox.centre(), glm::vec3(1.f, 2.f, 4.f));
    EXPECT_EQ(kBox.extent(), glm::vec3(4.f)); // edge lengths, not half-lengths
    EXPECT_FLOAT_EQ(kBox.boundingRadius(), 2.f * std::sqrt(3.f));
    const Aabb c = Aabb::cube(glm::vec3(1.f, 2.f, 3.f), 0.5f);
    EXPECT_EQ(c.min, glm::vec3(0.5f, 1.5f, 2.5f));
    EXPECT_EQ(c.max, glm::vec3(1.5f, 2.5f, 3.5f));
}

TEST(Aabb, ContainsAndOverlapsAreClosed) {
    EXPECT_TRUE(kBox.contains(kBox.min));
    EXPECT_TRUE(kBox.contains(kBox.max));
    EXPECT_TRUE(kBox.contains(glm::vec3(3.f, 2.f, 4.f))); // on the +X face
    EXPECT_FALSE(kBox.contains(glm::vec3(3.001f, 2.f, 4.f)));
    EXPECT_FALSE(kBox.contains(glm::vec3(1.f, 2.f, 1.999f)));
    EXPECT_TRUE(kBox.contains(Aabb::cube(glm::vec3(1.f, 2.f, 4.f), 2.f)));
    EXPECT_FALSE(kBox.contains(Aabb::cube(glm::vec3(1.f, 2.f, 4.f), 2.001f)));

    const Aabb touching{{3.f, 0.f, 2.f}, {5.f, 1.f, 3.f}}; // shares the +X face
    EXPECT_TRUE(kBox.overlaps(touching));
    EXPECT_TRUE(touching.overlaps(kBox));
    const Aabb apart = touching.translated(glm::vec3(0.001f, 0.f, 0.f));
    EXPECT_FALSE(kBox.overlaps(apart));
    EXPECT_FALSE(apart.overlaps(kBox));
    // Overlapping on two axes only is not overlapping.
    EXPECT_FALSE(kBox.overlaps(kBox.translated(glm::vec3(0.f, 0.f, 4.5f))));
}

TEST(Aabb, UnitCubeRotated45DegreesAboutYWidensBySqrt2) {
    const Aabb unit = Aabb::cube(glm::vec3(0.f), 0.5f);
    const glm::mat4 m = glm::translate(glm::mat4(1.f), glm::vec3(2.f, 3.f, 4.f)) *
                        glm::rotate(glm::mat4(1.f), glm::radians(45.f), glm::vec3(0, 1, 0));
    const Aabb w = unit.transformed(m);
    const float h = 0.5f * std::sqrt(2.f); // the half-diagonal of a unit square
    expectVecNear(w.min, glm::vec3(2.f - h, 2.5f, 4.f - h), 1e-6f);
    expectVecNear(w.max, glm::vec3(2.f + h, 3.5f, 4.f + h), 1e-6f);
}

TEST(Aabb, QuarterTurnSwapsAxesAndScaleTranslateIsExact) {
    const glm::mat4 quarter = glm::rotate(glm::mat4(1.f), glm::radians(90.f), glm::vec3(0, 0, 1));
    const Aabb b{{-1.f, -2.f, -3.f}, {1.f, 2.f, 3.f}};
    const Aabb r = b.transformed(quarter);
    expectVecNear(r.min, glm::vec3(-2.f, -1.f, -3.f), 1e-6f);
    expectVecNear(r.max, glm::vec3(2.f, 1.f, 3.f), 1e-6f);

    const glm::mat4 st = glm::translate(glm::mat4(1.f), glm::vec3(1.f, -1.f, 0.5f)) *
                         glm::scale(glm::mat4(1.f), glm::vec3(2.f, 3.f, -1.f));
    const Aabb s = kBox.transformed(st);
    // A negative scale flips the axis: z in [2, 6] becomes [-6, -2], then +0.5.
    EXPECT_EQ(s.min, glm::vec3(-1.f, -1.f, -5.5f));
    EXPECT_EQ(s.max, glm::vec3(7.f, 11.f, -1.5f));
}

TEST(Aabb, TransformedBoxHoldsEveryTransformedPointOfTheBox) {
    const glm::mat4 m =
        glm::translate(glm::mat4(1.f), glm::vec3(-3.f, 1.f, 2.f)) *
        glm::rotate(glm::mat4(1.f), 0.7f, glm::normalize(glm::vec3(1.f, 2.f, -0.5f))) *
        glm::scale(glm::mat4(1.f), glm::vec3(0.5f, 2.f, 1.5f));
    const Aabb w = kBox.transformed(m);
    const Aabb grown{w.min - 1e-5f, w.max + 1e-5f}; // float rounding of the corners
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    Aabb seen; // the points' own box reaches close to every face of the corner box
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 t(u(rng), u(rng), u(rng));
        // Mostly corners and edges, where the extremes of a rotated box lie.
        const glm::vec3 q = i % 2 ? glm::round(t) : t;
        const glm::vec3 p = glm::vec3(m * glm::vec4(kBox.min + q * kBox.extent(), 1.f));
        ASSERT_TRUE(grown.contains(p)) << i;
        seen.extend(p);
    }
    expectVecNear(seen.min, w.min, 1e-5f);
    expectVecNear(seen.max, w.max, 1e-5f);
}

TEST(Aabb, DistanceIsZeroInsideAndEuclideanOutside) {
    EXPECT_EQ(kBox.distance(kBox.centre()), 0.f);
    EXPECT_EQ(kBox.distance(kBox.max), 0.f);
    EXPECT_FLOAT_EQ(kBox.distance(glm::vec3(1.f, 2.f, 8.5f)), 2.5f); // off the +Z face
    EXPECT_FLOAT_EQ(kBox.distance(glm::vec3(-3.f, 2.f, 4.f)), 2.f);  // off the -X face
    EXPECT_FLOAT_EQ(kBox.distance(kBox.max + 1.f), std::sqrt(3.f));  // off a corner
    EXPECT_FLOAT_EQ(kBox.distance(glm::vec3(6.f, 8.f, 4.f)), 5.f);   // off an edge: 3-4-5
}

TEST(Aabb, OverhangIsHowFarABoxSticksOutOfAnother) {
    const Aabb cell = Aabb::cube(glm::vec3(1.f, 1.f, 1.f), 0.75f);
    const Aabb ball = Aabb::cube(glm::vec3(1.f, 1.f, 1.f), 0.25f);
    EXPECT_FLOAT_EQ(ball.overhang(cell), -0.5f); // inside, 0.5 m from every face
    EXPECT_FLOAT_EQ(ball.translated(glm::vec3(0.7f, 0.f, 0.f)).overhang(cell), 0.2f);
    EXPECT_FLOAT_EQ(ball.translated(glm::vec3(0.f, 0.f, -0.6f)).overhang(cell), 0.1f);
    // The worst axis decides.
    EXPECT_FLOAT_EQ(ball.translated(glm::vec3(0.6f, -0.9f, 0.f)).overhang(cell), 0.4f);
    EXPECT_FLOAT_EQ(cell.overhang(cell), 0.f);
    // A box larger than the cell sticks out even when centred in it.
    EXPECT_FLOAT_EQ(Aabb::cube(glm::vec3(1.f), 1.f).overhang(cell), 0.25f);
}
