// The effect plan on generated scenes of many nodes (issue 10: it was quadratic, 2,000 nodes
// planned in 12 s). Each row builds a scene of N small boxes scattered 2-20 m around the probe,
// then times reading the markup and planning: a figure for CI's log, not an assertion.
#include "assetcooker/lib/plan/effect_plan.h"
#include "tests/plan/code_scene.h"

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>

using namespace specula;

namespace {

std::shared_ptr<MeshData> unitBox() {
    auto m = std::make_shared<MeshData>();
    for (int i = 0; i < 8; ++i)
        m->positions.push_back(
            glm::vec3((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f));
    const unsigned quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (const auto& q : quads)
        for (unsigned k : {q[0], q[1], q[2], q[0], q[2], q[3]})
            m->indices.push_back(k);
    m->boundsMin = glm::vec3(-0.5f);
    m->boundsMax = glm::vec3(0.5f);
    return m;
}

struct GeneratedScene : test::CodeScene {
    explicit GeneratedScene(int boxes) {
        const auto box = unitBox();
        node("mirror", glm::vec3(0.f), box, "{\"specula_reflector\": true}", 0.5f);
        node("probe", glm::vec3(0.f), nullptr, "{\"specula_probe\": {\"cell_size\": 1.0}}");
        std::mt19937 rng(1);
        std::uniform_real_distribution<float> coord(-20.f, 20.f), size(0.05f, 0.4f);
        for (int i = 0; i < boxes; ++i) {
            glm::vec3 p;
            do
                p = glm::vec3(coord(rng), coord(rng), coord(rng));
            while (glm::dot(p, p) < 4.f);
            node("box" + std::to_string(i), p, box, "", size(rng));
        }
        updateWorldTransforms(reg);
    }
};

void BM_PlanGeneratedScene(benchmark::State& state) {
    GeneratedScene g(int(state.range(0)));
    std::size_t layers = 0;
    for (auto _ : state) {
        const SceneMarkup m = readSceneMarkup(g.reg, g.scene, "generated.gltf");
        const glm::vec3 c = markupProbeCentre(g.reg, m, g.scene);
        const EffectPlan plan =
            planEffects(g.reg, m, c, markupReflectorReach(g.reg, m, c, markupCellSize(m)));
        layers = plan.layers.size();
        benchmark::DoNotOptimize(layers);
    }
    state.counters["layers"] = double(layers);
    state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_PlanGeneratedScene)
    ->Arg(1000)
    ->Arg(5000)
    ->Arg(20000)
    ->Unit(benchmark::kMillisecond)
    ->Complexity();

} // namespace

BENCHMARK_MAIN();
