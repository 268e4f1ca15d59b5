#pragma once
// A level of distance probes as one probe entity: its ReflectionProbe's asset is a baked
// level's index (DIR/level.json, level_index.h) and it may hold a DistanceLevel (defaults
// when it does not). Every Reflector pointing at it blends up to `k` of the level's probes
// per pixel (shaders/distance_level_blend.glsl.h): DistanceLevelStore draws it, and
// CpuDistanceLevel is its CPU twin.
#include "components/reflection_probe/distance/distance_probe.h"

#include <cstddef>
#include <string>

namespace specula {

enum class LevelBlend { Nearest, Engine, Visibility };
const char* toString(LevelBlend b);

struct DistanceLevel {
    // Every probe's lookup: a single-layer method (envmap, boxproj, bisection, secant).
    DistanceProbe lookup{DistanceMethod::Secant};
    LevelBlend blend = LevelBlend::Visibility;
    int k = 4; // probes blended per pixel at most, 1 .. kMaxLevelK (a shader permutation)

    bool operator==(const DistanceLevel&) const = default;
};

// Throws Error naming `file` and the field when the settings cannot drive a level: a method
// that is not single-layer, or k outside 1 .. kMaxLevelK.
void validateDistanceLevel(const DistanceLevel& settings, const std::string& file);

// Throws Error naming the level `file` and probes[probe] when that probe's face resolution
// differs from the level's first: one cube-map array holds every probe of a level.
void checkLevelFaceRes(int faceRes, int levelFaceRes, const std::string& file, std::size_t probe);

} // namespace specula
