#include "engine/ecs/registry.h"

#include <gtest/gtest.h>

#include <set>

using namespace specula::ecs;

namespace {
struct Position {
    float x = 0, y = 0;
};
struct Velocity {
    float dx = 0, dy = 0;
};
struct Tag {};
} // namespace

TEST(Registry, CreateDestroyReuseBumpsGeneration) {
    Registry reg;
    Entity a = reg.create();
    Entity b = reg.create();
    EXPECT_NE(a, b);
    EXPECT_TRUE(reg.valid(a));
    reg.destroy(a);
    EXPECT_FALSE(reg.valid(a));
    Entity c = reg.create(); // reuses a's slot
    EXPECT_EQ(c.index, a.index);
    EXPECT_EQ(c.generation, a.generation + 1);
    EXPECT_TRUE(reg.valid(c));
    EXPECT_FALSE(reg.valid(a)) << "a stale handle must not alias the new entity";
    EXPECT_EQ(reg.alive(), 2u);
}

TEST(Registry, StaleHandleSeesNoComponentsAndDestroyIsNoop) {
    Registry reg;
    Entity a = reg.create();
    reg.emplace<Position>(a, 1.f, 2.f);
    reg.destroy(a);
    Entity c = reg.create();
    reg.emplace<Position>(c, 5.f, 6.f);
    EXPECT_EQ(reg.find<Position>(a), nullptr);
    EXPECT_FALSE(reg.has<Position>(a));
    reg.destroy(a); // stale: must not destroy c
    EXPECT_TRUE(reg.valid(c));
    ASSERT_NE(reg.find<Position>(c), nullptr);
    EXPECT_EQ(reg.get<Position>(c).x, 5.f);
}

TEST(Registry, DestroyRemovesComponents) {
    Registry reg;
    Entity a = reg.create();
    reg.emplace<Position>(a);
    reg.emplace<Velocity>(a);
    reg.destroy(a);
    EXPECT_EQ(reg.view<Position>().count(), 0u);
    EXPECT_EQ(reg.view<Velocity>().count(), 0u);
}

TEST(View, SkipsEntitiesMissingAComponent) {
    Registry reg;
    std::set<std::uint32_t> both;
    for (int i = 0; i < 100; ++i) {
        Entity e = reg.create();
        reg.emplace<Position>(e, float(i), 0.f);
        if (i % 3 == 0) {
            reg.emplace<Velocity>(e, 1.f, 0.f);
            both.insert(e.index);
        }
    }
    std::set<std::uint32_t> seen;
    reg.view<Position, Velocity>().each([&](Entity e, Position& p, Velocity& v) {
        EXPECT_EQ(p.x, float(e.index));
        EXPECT_EQ(v.dx, 1.f);
        seen.insert(e.index);
    });
    EXPECT_EQ(seen, both);
    EXPECT_EQ((reg.view<Position, Tag>().count()), 0u) << "a never-used component type";
}

TEST(View, RemovalDuringIterationIsSafe) {
    Registry reg;
    for (int i = 0; i < 10; ++i)
        reg.emplace<Position>(reg.create());
    reg.view<Position>().each([&](Entity e, Position&) { reg.remove<Position>(e); });
    EXPECT_EQ(reg.view<Position>().count(), 0u);
}

TEST(SparseSet, SwapRemoveKeepsOthersReachable) {
    Registry reg;
    std::vector<Entity> es;
    for (int i = 0; i < 5; ++i) {
        es.push_back(reg.create());
        reg.emplace<Position>(es.back(), float(i), 0.f);
    }
    reg.remove<Position>(es[1]);
    for (int i = 0; i < 5; ++i) {
        if (i == 1) continue;
        ASSERT_TRUE(reg.has<Position>(es[i]));
        EXPECT_EQ(reg.get<Position>(es[i]).x, float(i));
    }
}
