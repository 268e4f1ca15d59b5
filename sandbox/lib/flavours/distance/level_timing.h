#pragma once
// The GPU side of specula-sandbox level (level_walk.h): the level shader's reflector pass for
// every blend and K = 1, 2, 4, timed against one probe's envmap pass.
#include "components/reflection_probe/distance/distance_probe.h"
#include "engine/math/camera.h"
#include "sandbox/lib/flavours/distance/level_walk.h"

#include <string>
#include <vector>

namespace specula {
class ReflectionScene;
}

namespace specula::sandbox {

// The level shader's reflector pass for every blend and K = 1, 2, 4 against one probe's
// mirror envmap pass (the probe nearest to `reflector`), all from `camera` with the reflector
// where it is now; the level's passes with every reflector at `roughness` (> 0: the glossy
// permutation, which reads every probe's chain), the envmap's with mirrors; at roughness > 0
// also the mirror level's visibility blend at K = 4 ("visibility (mirror)"). Needs a current
// GL context. `timer`: what clock measured them.
std::vector<LevelPassTime> timeLevelPasses(ReflectionScene& rs, const std::string& levelDir,
                                           const DistanceProbe& lookup, const CameraView& camera,
                                           glm::vec3 reflector, float roughness,
                                           std::string& timer);

} // namespace specula::sandbox
