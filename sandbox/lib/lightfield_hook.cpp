#include "lightfield_hook.h"

#include "engine/core/error.h"

#if __has_include("assetcooker/lib/lightfield_bake.h")
#include "assetcooker/lib/lightfield_bake.h"
#define SPECULA_SANDBOX_HAS_LIGHTFIELD 1
#else
#define SPECULA_SANDBOX_HAS_LIGHTFIELD 0
#endif

#include <chrono>

namespace specula {

bool lightFieldBakeAvailable() {
    return SPECULA_SANDBOX_HAS_LIGHTFIELD != 0;
}

LightFieldBake bakeLightField(ReflectionScene& scene, const std::string& dir, int cameras,
                              int res) {
    LightFieldBake b;
    b.params = "num=" + std::to_string(cameras) + " res=" + std::to_string(res);
#if SPECULA_SANDBOX_HAS_LIGHTFIELD
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
#else
    (void)scene;
    (void)dir;
    (void)cameras;
    (void)res;
#endif
    return b;
}

std::vector<LightFieldBake> bakeLightFieldsForBench(ReflectionScene& scene,
                                                    const std::string& dirRoot, bool quick) {
    std::vector<LightFieldBake> out;
    if (!lightFieldBakeAvailable()) return out;
    const std::vector<std::pair<int, int>> sizes =
        quick ? std::vector<std::pair<int, int>>{{8, 16}}
              : std::vector<std::pair<int, int>>{{8, 32}, {16, 64}};
    for (auto [cameras, res] : sizes)
        out.push_back(bakeLightField(
            scene, dirRoot + "_" + std::to_string(cameras) + "x" + std::to_string(res), cameras,
            res));
    return out;
}

std::string manifestFlavour(const std::string& manifest) {
#if SPECULA_SANDBOX_HAS_LIGHTFIELD
    return probeManifestFlavour(manifest);
#else
    (void)manifest;
    return "distance";
#endif
}

} // namespace specula
