#include "sandbox/lib/flavours/lightfield/lightfield_hook.h"

#include "sandbox/lib/render/scene_cook.h"

namespace specula {

LightFieldBake bakeLightField(ReflectionScene& scene, const std::string& dir, int cameras, int res,
                              bool showProgress, std::ostream* log) {
    LightFieldBake b;
    b.params = "num=" + std::to_string(cameras) + " res=" + std::to_string(res);
    LightFieldCookSettings s;
    s.cameras = cameras;
    s.imageRes = res;
    const CookResult r = cookSceneInto(scene, dir, s, showProgress, log);
    b.seconds = r.bakeSeconds;
    b.manifest = r.manifest;
    return b;
}

std::vector<LightFieldBake> bakeLightFieldsForBench(ReflectionScene& scene,
                                                    const std::string& dirRoot, bool quick,
                                                    std::ostream* log) {
    std::vector<LightFieldBake> out;
    const std::vector<std::pair<int, int>> sizes =
        quick ? std::vector<std::pair<int, int>>{{8, 16}}
              : std::vector<std::pair<int, int>>{{8, 32}, {16, 64}};
    for (auto [cameras, res] : sizes)
        out.push_back(bakeLightField(
            scene, dirRoot + "_" + std::to_string(cameras) + "x" + std::to_string(res), cameras,
            res, false, log));
    return out;
}

} // namespace specula
