#include "plan_command.h"

#include "assetcooker/lib/effect_plan.h"
#include "engine/scene/gltf_loader.h"

#include <memory>
#include <optional>

namespace specula::cook {

namespace {

struct PlanArgs {
    std::string scene;
    std::optional<std::string> probe;
    std::optional<float> maxErrorDeg;
    bool json = false;
};

int runPlan(const PlanArgs& a, std::ostream& out) {
    PlanThresholds t;
    if (a.maxErrorDeg) t.maxErrorDeg = *a.maxErrorDeg;
    ecs::Registry registry;
    const LoadedScene scene = loadGltf(a.scene, registry);
    const SceneMarkup markup = readSceneMarkup(registry, scene, a.scene);
    const glm::vec3 centre =
        a.probe ? cli::parseVec3(*a.probe) : markupProbeCentre(registry, markup, scene);
    const float reach = markupReflectorReach(registry, markup, centre, markupCellSize(markup));
    const EffectPlan plan = planEffects(registry, markup, centre, reach, t);
    if (a.json)
        out << plan.toJson().dump(2) << "\n";
    else
        out << plan.toText();
    return cli::kExitOk;
}

} // namespace

void addPlanCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<PlanArgs>();
    CLI::App* sub = tool.addSubcommand(
        "plan", "print the effect plan of a scene's probe (what it needs, and why)",
        "Prints which reflection effects the probe of SCENE needs, with the reason for each\n"
        "decision, without baking: distant objects -> direction-only lookup; large near objects\n"
        "-> per-pixel rectification; small near ones -> average distance; layers only where\n"
        "objects overlap as seen from the reflector cell; Fresnel only where a reflector's F0 < "
        "1.\n"
        "Rough reflectors: where the sharpest reflector's GGX lobe (half-width 2 atan(r^2)) is\n"
        "wider than an object's parallax, or than the band an occluder uncovers, the cheaper\n"
        "lookup (direction only; one merged layer; no light field) is chosen, with the reason.\n"
        "Needs stated in the probe node's extras (\"specula_probe\": {\"max_error_deg\": 0.5,\n"
        "\"motion_range\": 1.5, \"flavour\": \"distance\"|\"lightfield\", \"fresnel\": true,\n"
        "\"background\": true}) are honoured and reported.\n",
        "exit status: 0 ok, 1 the scene could not be read, 2 bad command line\n",
        [a](std::ostream& out) { return runPlan(*a, out); });
    sub->add_option("SCENE", a->scene, "the glTF/GLB scene")->required();
    sub->add_option("--probe", a->probe, "probe centre (overrides the markup)")
        ->check(cli::vec3Text());
    sub->add_option("--max-error-deg", a->maxErrorDeg,
                    "direction-only error allowed, degrees (default 1, or the markup)")
        ->check(cli::finiteRange(1e-3, 45.0));
    sub->add_flag("--json", a->json, "print JSON instead of text");
}

} // namespace specula::cook
