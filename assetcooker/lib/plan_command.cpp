#include "plan_command.h"

#include "assetcooker/lib/cli.h"
#include "assetcooker/lib/effect_plan.h"
#include "engine/core/flags.h"
#include "engine/scene/gltf_loader.h"

namespace specula::cook {

const std::string_view kPlanUsage =
    "usage: specula-cook plan SCENE [options]\n"
    "\n"
    "Prints which reflection effects the probe of SCENE needs, with the reason for each\n"
    "decision, without baking: distant objects -> direction-only lookup; large near objects\n"
    "-> per-pixel rectification; small near ones -> average distance; layers only where\n"
    "objects overlap as seen from the reflector cell; Fresnel only where a reflector's F0 < 1.\n"
    "Needs stated in the probe node's extras (\"specula_probe\": {\"max_error_deg\": 0.5,\n"
    "\"motion_range\": 1.5, \"flavour\": \"distance\"|\"lightfield\", \"fresnel\": true,\n"
    "\"background\": true}) are honoured and reported.\n"
    "\n"
    "options:\n"
    "  --probe x,y,z        probe centre (overrides the markup)\n"
    "  --max-error-deg E    direction-only error allowed, degrees (default 1, or the markup)\n"
    "  --json               print JSON instead of text\n"
    "  -h, --help           show this help\n"
    "\n"
    "exit status: 0 ok, 1 the scene could not be read, 2 bad command line\n";

int runPlan(std::span<const std::string> args, std::ostream& out, std::ostream&) {
    Flags flags(args);
    const auto probeAt = flags.vec3Value("--probe");
    const auto maxError = flags.value("--max-error-deg");
    const bool json = flags.flag("--json");
    const auto pos = flags.positionals();
    if (pos.size() != 1) throw UsageError{"plan needs exactly one SCENE"};
    PlanThresholds t;
    if (maxError) t.maxErrorDeg = parseFloat("--max-error-deg", *maxError, 1e-3f, 45.f);

    ecs::Registry registry;
    const LoadedScene scene = loadGltf(pos[0], registry);
    const SceneMarkup markup = readSceneMarkup(registry, scene, pos[0]);
    const glm::vec3 centre = probeAt ? *probeAt : markupProbeCentre(registry, markup, scene);
    const float reach = markupReflectorReach(registry, markup, centre, markupCellSize(markup));
    const EffectPlan plan = planEffects(registry, markup, centre, reach, t);
    if (json)
        out << plan.toJson().dump(2) << "\n";
    else
        out << plan.toText();
    return kExitOk;
}

} // namespace specula::cook
