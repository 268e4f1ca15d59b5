#include "sandbox/lib/render/scene_cook.h"

namespace specula {

CookResult cookSceneInto(ReflectionScene& scene, const std::string& dir, const CookFlavour& flavour,
                         bool showProgress, std::ostream* log) {
    CookOptions o;
    o.out = dir;
    o.flavour = flavour;
    o.progress = showProgress;
    return cookProbe(scene.probeScene(), o, log);
}

} // namespace specula
