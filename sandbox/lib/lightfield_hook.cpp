#include "lightfield_hook.h"

#include "assetcooker/lib/lightfield_bake.h"

#include <chrono>

namespace specula {

LightFieldBake bakeLightField(ReflectionScene& scene, const std::string& dir, int cameras,
                              int res) {
    LightFieldBake b;
    b.params = "num=" + std::to_string(cameras) + " res=" + std::to_string(res);
    const auto t0 = std::chrono::steady_clock::now();
    LightFieldBakeOptions o;
    o.cellCentre = scene.probeCentre();
    o.cellSize = scene.cellSize();
    o.cameras = cameras;
    o.res = res;
    o.sky = scene.sky().empty() ? nullptr : &scene.sky();
    const LightFieldAsset asset = bakeLightFieldProbe(scene.registry(), scene.markup(), o);
    b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    writeLightFieldProbe(asset, dir, scene.path());
    b.manifest = dir + "/manifest.json";
    return b;
}

std::vector<LightFieldBake> bakeLightFieldsForBench(ReflectionScene& scene,
                                                    const std::string& dirRoot, bool quick) {
    std::vector<LightFieldBake> out;
    const std::vector<std::pair<int, int>> sizes =
        quick ? std::vector<std::pair<int, int>>{{8, 16}}
              : std::vector<std::pair<int, int>>{{8, 32}, {16, 64}};
    for (auto [cameras, res] : sizes)
        out.push_back(bakeLightField(
            scene, dirRoot + "_" + std::to_string(cameras) + "x" + std::to_string(res), cameras,
            res));
    return out;
}

} // namespace specula
