#pragma once
// How the sandbox bakes light-field probes: the bench sweeps the cooked sizes below and
// walk bakes one when asked for --method lightfield.
#include "sandbox/lib/render/reflection_scene.h"

#include <ostream>
#include <string>
#include <vector>

namespace specula {

struct LightFieldBake {
    std::string manifest;
    std::string params; // e.g. "num=16 res=64"
    double seconds = 0;
    double fetchesPerPixel = 4; // quadrilinear: 4 bilinear fetches per ray (docs/design.md §5)
};

// The bench's light-field sweep (one bake per size), into dirRoot_<params>.
std::vector<LightFieldBake> bakeLightFieldsForBench(ReflectionScene& scene,
                                                    const std::string& dirRoot, bool quick,
                                                    std::ostream* log = nullptr);
// One light field for walk (cameras x res), into dir, through the cooking API (cookProbe).
LightFieldBake bakeLightField(ReflectionScene& scene, const std::string& dir, int cameras, int res,
                              bool showProgress = false, std::ostream* log = nullptr);

} // namespace specula
