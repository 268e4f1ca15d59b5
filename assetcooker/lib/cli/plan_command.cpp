#include "assetcooker/lib/cli/plan_command.h"

#include "assetcooker/lib/cli/setting_flags.h"
#include "assetcooker/lib/plan/plan_measure.h"
#include "assetcooker/lib/scene/probe_setup.h"
#include "engine/core/error.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

namespace specula::cook {

namespace {

// The bake's settings this command takes: the measured plan's (the distance flavour's
// declaration, so a flag means here what it means to `bake`).
const std::vector<std::string> kBakeFlags = {"--plan", "--max-error", "--max-mib-per-probe",
                                             "--face-res"};

struct PlanArgs {
    std::string scene;
    std::optional<std::string> probe, sky;
    std::optional<float> maxErrorDeg, cellSize;
    int rays = 32768;
    float viewShare = kDefaultViewShare;
    std::uint32_t seed = 1;
    bool json = false;
    SettingFlags flags;
};

int runPlan(const PlanArgs& a, std::ostream& out) {
    const auto start = std::chrono::steady_clock::now();
    // The flags are checked before the scene is opened: a usage error names them.
    const auto settings =
        std::get<DistanceCookSettings>(a.flags.settings(DistanceCookSettings::kFlavour, a.scene));
    const std::string kind = settings.measuredPlan ? "measured" : "analytic";
    PlanThresholds t;
    if (a.maxErrorDeg) t.maxErrorDeg = *a.maxErrorDeg;
    ProbeScene scene(a.scene, a.sky.value_or(""));
    const glm::vec3 centre = a.probe
                                 ? cli::parseVec3(*a.probe)
                                 : markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    const float cell = a.cellSize.value_or(markupCellSize(scene.markup));
    const float reach = markupReflectorReach(scene.registry, scene.markup, centre, cell);
    EffectPlan plan = planEffects(scene.registry, scene.markup, centre, reach, t);
    if (settings.measuredPlan) {
        MeasuredPlanOptions m;
        m.faceRes = settings.faceRes;
        m.rays = a.rays;
        m.seed = a.seed;
        m.budget = settings.maxError ? *settings.maxError : markupErrorBudget(scene.markup, 0);
        m.sky = scene.sky.empty() ? nullptr : &scene.sky;
        m.cellSize = cell;
        m.eyes = sceneEyes(scene);
        m.viewShare = a.viewShare;
        m.maxMibPerProbe = settings.maxMibPerProbe.value_or(0.0);
        m.formats = planFormatsFor(false, m.maxMibPerProbe);
        plan = applyMeasurement(plan,
                                measurePlan(scene.registry, scene.markup, plan, centre, reach, m));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (a.json) {
        nlohmann::json j = plan.toJson();
        j["plan_kind"] = kind;
        j["plan_seconds"] = seconds;
        out << j.dump(2) << "\n";
    } else {
        char line[96];
        std::snprintf(line, sizeof line, "plan time  %.2f s (%s, scene loading included)\n",
                      seconds, kind.c_str());
        out << plan.toText() << line;
    }
    return cli::kExitOk;
}

} // namespace

void addPlanCommand(cli::ToolCli& tool) {
    auto a = std::make_shared<PlanArgs>();
    CLI::App* sub = tool.addSubcommand(
        "plan", "print the effect plan of a scene's probe (what it needs, and why)",
        "Prints which reflection effects the probe of SCENE needs, with the reason for each\n"
        "decision. --plan measured (the default) bakes the probes the candidates need (the\n"
        "composite and the analytic plan's layers, at --face-res and half of it), scores every\n"
        "runtime configuration (envmap, boxproj, avgdist, bisection / secant / march at d_e\n"
        "0.1, 0.03, 0.01, layered) with the CPU twin against Embree on --rays stratified\n"
        "reflector rays, predicts each one's pass time from a cost model fitted to the bench,\n"
        "and keeps the cheapest meeting --max-error (else the markup's \"max_error\"; else the\n"
        "cheapest within 0.5 dB of the best). It lists every candidate and why the winner won.\n"
        "--plan analytic: the thresholds alone: distant objects -> direction-only lookup; large\n"
        "near objects -> per-pixel rectification; small near ones -> average distance; layers\n"
        "only where objects overlap as seen from the reflector cell; Fresnel only where a\n"
        "reflector's F0 < 1; rough reflectors: where the sharpest GGX lobe is wider than the\n"
        "parallax, the cheaper lookup. Needs stated in the probe node's extras\n"
        "(\"specula_probe\": {\"max_error\": \"32dB\", \"max_error_deg\": 0.5, \"motion_range\":\n"
        "1.5, \"flavour\": \"distance\"|\"lightfield\", \"fresnel\": true, \"background\": true})\n"
        "are honoured and reported.\n",
        "exit status: 0 ok, 1 the scene could not be read, 2 bad command line\n",
        [a](std::ostream& out) { return runPlan(*a, out); });
    sub->add_option("SCENE", a->scene, "the glTF/GLB scene")->required();
    sub->add_option("--probe", a->probe, "probe centre (overrides the markup)")
        ->check(cli::vec3Text());
    tool.allowEmpty(
        sub->add_option("--sky", a->sky, "equirectangular panorama (default and '': a black sky)"));
    a->flags.add(tool, sub, DistanceCookSettings::kFlavour, kBakeFlags);
    sub->add_option("--rays", a->rays, "measured plan: reflector rays sampled")
        ->check(CLI::Range(64, 1 << 20));
    sub->add_option("--cell-size", a->cellSize,
                    "the cell the reflectors move in, metres (default: the markup's cell_size, "
                    "else 1.5; 0: reflectors at rest)")
        ->check(cli::finiteRange(0.0, 1e4));
    sub->add_option(
           "--view-share", a->viewShare,
           "measured plan: share of the draws reflecting the scene camera's view (default\n"
           "0.5; the rest cosine-weighted over the hemisphere)")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_option("--seed", a->seed, "measured plan: the ray sample's seed");
    sub->add_option("--max-error-deg", a->maxErrorDeg,
                    "direction-only error allowed, degrees (default 1, or the markup)")
        ->check(cli::finiteRange(1e-3, 45.0));
    sub->add_flag("--json", a->json, "print JSON instead of text");
}

} // namespace specula::cook
