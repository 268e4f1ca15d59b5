#pragma once
// The cooking API (cookProbe) on the sandbox's scene, for every part of the sandbox that bakes a
// probe (the walk's source, each flavour's bench rows).
#include "assetcooker/lib/bake/cook.h"
#include "sandbox/lib/render/reflection_scene.h"

#include <ostream>
#include <string>

namespace specula {

// `flavour`'s probe of `scene` into `dir` (replaced). `log`: the cook's warnings (null: dropped).
CookResult cookSceneInto(ReflectionScene& scene, const std::string& dir, const CookFlavour& flavour,
                         bool showProgress, std::ostream* log);

} // namespace specula
