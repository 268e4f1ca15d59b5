#include "distance_level.h"

#include "engine/core/error.h"
#include "engine/core/glsl_host.h"

namespace specula {
namespace glsl {
#include "components/reflection_probe/distance/shaders/distance_level_params.glsl.h"
} // namespace glsl

static_assert(int(LevelBlend::Nearest) == glsl::kLevelBlendNearest &&
              int(LevelBlend::Engine) == glsl::kLevelBlendEngine &&
              int(LevelBlend::Visibility) == glsl::kLevelBlendVisibility);

const char* toString(LevelBlend b) {
    switch (b) {
    case LevelBlend::Nearest:
        return "nearest";
    case LevelBlend::Engine:
        return "engine";
    case LevelBlend::Visibility:
        return "visibility";
    }
    return "?";
}

void validateDistanceLevel(const DistanceLevel& s, const std::string& file) {
    const DistanceMethod m = s.lookup.method;
    if (m == DistanceMethod::Layered || m == DistanceMethod::Planned ||
        m == DistanceMethod::AvgDist)
        throw Error(file, "method",
                    std::string("a level blends single-layer lookups: ") + toString(m) +
                        " is not one (envmap, boxproj, bisection, secant)");
    if (s.k < 1 || s.k > glsl::kMaxLevelK)
        throw Error(file, "k",
                    "probes blended per pixel must be 1 .. " + std::to_string(glsl::kMaxLevelK) +
                        ", got " + std::to_string(s.k));
}

void checkLevelFaceRes(int faceRes, int levelFaceRes, const std::string& file, std::size_t probe) {
    if (faceRes != levelFaceRes)
        throw Error(file, "probes[" + std::to_string(probe) + "]",
                    "face resolution " + std::to_string(faceRes) + " differs from the level's " +
                        std::to_string(levelFaceRes) +
                        " (one texture array holds every probe): re-bake the level");
}

} // namespace specula
