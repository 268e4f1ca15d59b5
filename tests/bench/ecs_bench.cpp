// Iteration cost of the ECS: 100k entities, a view over two of three component types.
#include "engine/ecs/registry.h"

#include <benchmark/benchmark.h>

using namespace specula::ecs;

namespace {
struct Position {
    float x, y, z;
};
struct Velocity {
    float x, y, z;
};
struct Health {
    int hp;
};

void BM_View2Of100k(benchmark::State& state) {
    Registry reg;
    const int n = int(state.range(0));
    for (int i = 0; i < n; ++i) {
        Entity e = reg.create();
        reg.emplace<Position>(e, 0.f, 0.f, 0.f);
        reg.emplace<Velocity>(e, 1.f, 2.f, 3.f);
        if (i % 2) reg.emplace<Health>(e, 100);
    }
    for (auto _ : state) {
        reg.view<Position, Velocity>().each([](Entity, Position& p, Velocity& v) {
            p.x += v.x;
            p.y += v.y;
            p.z += v.z;
        });
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_View2Of100k)->Arg(100000)->Unit(benchmark::kMicrosecond);

void BM_CreateDestroy(benchmark::State& state) {
    Registry reg;
    for (auto _ : state) {
        Entity e = reg.create();
        reg.emplace<Position>(e, 0.f, 0.f, 0.f);
        reg.destroy(e);
    }
}
BENCHMARK(BM_CreateDestroy);
} // namespace

BENCHMARK_MAIN();
