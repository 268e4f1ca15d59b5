#include "assetcooker/lib/bake/cook.h"

#include "assetcooker/lib/bake/cook_settings_json.h"
#include "assetcooker/lib/flavours/distance/distance_bake.h"
#include "assetcooker/lib/plan/effect_plan.h"
#include "assetcooker/lib/plan/plan_measure.h"
#include "assetcooker/lib/scene/probe_inputs.h"
#include "components/reflection_probe/distance/distance_compression.h"
#include "components/reflection_probe/distance/writer/distance_probe_writer.h"
#include "components/reflection_probe/lightfield/writer/lightfield_probe_writer.h"
#include "components/reflection_probe/pem/writer/pem_compression.h"
#include "components/reflection_probe/pem/writer/pem_probe_writer.h"
#include "components/reflection_probe/writer/probe_folder.h"
#include "engine/core/error.h"
#include "engine/core/progress.h"

#include <chrono>
#include <filesystem>
#include <sstream>

namespace specula {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Before any work: repair what killed bakes left beside DIR (a line each on the log), and
// refuse a DIR that may not be replaced now rather than after a long bake.
void prepareOutput(const CookOptions& o, std::ostream* log) {
    std::ostringstream dropped;
    removeStaleProbeTemporaries(o.out, log ? *log : dropped);
    checkProbeFolderReplaceable(o.out, o.scene);
}

// Runs a baker with the options every flavour shares: the cancel poll, the placement
// warnings (on the log too) and a progress bar. Polled cancelled, the bakers stop with a
// plain Error; reported as the cancel it is, naming DIR.
template <class BakeOptions, class Bake>
auto bakeShared(const CookOptions& o, const std::string& label, BakeOptions& b, CookResult& result,
                std::ostream* log, Bake&& bake) {
    b.cancelled = [] { return cancelRequested(); };
    b.warnings = &result.warnings;
    std::optional<ProgressBar> bar;
    if (o.progressHook) {
        b.progress = o.progressHook;
    } else if (o.progress) {
        bar.emplace(label + " " + std::filesystem::path(o.scene).filename().string());
        b.progress = [&](double f) { bar->update(f); };
    }
    auto asset = [&] {
        try {
            return bake();
        } catch (const Error&) {
            throwIfCancelled(o.out);
            throw;
        }
    }();
    bar.reset();
    if (log)
        for (const std::string& w : result.warnings)
            *log << "  warning: " << w << '\n';
    throwIfCancelled(o.out);
    return asset;
}

void cookWith(ProbeScene& scene, const CookOptions& o, const DistanceCookSettings& s,
              CookResult& result, std::ostream* log) {
    const auto start = Clock::now();
    DistanceBakeOptions b;
    b.centre = o.probeCentre ? *o.probeCentre
                             : markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    b.faceRes = s.faceRes;
    b.sky = scene.sky.empty() ? nullptr : &scene.sky;
    b.reflectorReach = markupReflectorReach(scene.registry, scene.markup, b.centre,
                                            o.cellSize.value_or(markupCellSize(scene.markup)));
    b.proxy = o.proxy;
    std::string planJson, planLine; // the line goes to the log once the probe is written
    bool planCompressed = false;    // the measured plan chose BC6H under a memory budget
    if (s.planned || s.recordPlan) {
        EffectPlan plan = planEffects(scene.registry, scene.markup, b.centre, b.reflectorReach, {},
                                      o.markupProbe);
        if (s.planned && s.measuredPlan) {
            MeasuredPlanOptions m;
            m.faceRes = s.faceRes;
            m.seed = s.planSeed;
            m.budget = s.maxError ? *s.maxError : markupErrorBudget(scene.markup, o.markupProbe);
            m.sky = b.sky;
            m.cellSize = o.cellSize.value_or(markupCellSize(scene.markup));
            m.proxy = o.proxy;
            m.eyes = sceneEyes(scene);
            m.viewShare = kDefaultViewShare;
            m.maxMibPerProbe = s.maxMibPerProbe.value_or(0.0);
            m.formats =
                planFormatsFor(s.compression == DistanceCompression::Bc6h, m.maxMibPerProbe);
            // The second sample only measures the noise (`specula-cook plan` reports it): the
            // cook keeps its time for the choice.
            m.measureNoise = false;
            const MeasuredPlan measured =
                measurePlan(scene.registry, scene.markup, plan, b.centre, b.reflectorReach, m);
            if (!measured.warning.empty()) result.warnings.push_back(measured.warning);
            if (measured.chosen()) {
                std::ostringstream line;
                line << "measured plan: " << measured.chosen()->label() << " of "
                     << measured.candidates.size() << " candidates on " << measured.rays
                     << " rays in " << measured.seconds << " s (" << measured.reason << ")\n";
                planLine = line.str();
            }
            plan = applyMeasurement(plan, measured);
        }
        if (s.planned) applyPlan(plan, b);
        planCompressed = s.planned && plan.compressed;
        if (s.recordPlan) planJson = plan.toJson().dump();
    }
    throwIfCancelled(o.out);
    DistanceProbeAsset asset = bakeShared(o, "baking", b, result, log, [&] {
        return bakeDistanceProbe(scene.registry, scene.markup, b);
    });
    result.bakeSeconds = secondsSince(start);
    if (s.glossy == GlossyBake::On ||
        (s.glossy == GlossyBake::Auto && hasGlossyReflector(scene.markup))) {
        const auto prefilterStart = Clock::now();
        if (log)
            *log << "prefiltering the composite for glossy reflectors (GGX, "
                 << s.prefilter.levels - 1 << " levels)..." << std::flush;
        prefilterComposite(asset, s.prefilter); // seconds, no progress of its own
        result.prefilterSeconds = secondsSince(prefilterStart);
        if (log) *log << " " << result.prefilterSeconds << " s\n";
        throwIfCancelled(o.out);
    }
    asset.effectPlan = planJson;
    if (s.compression == DistanceCompression::Bc6h || planCompressed) {
        const auto compressStart = Clock::now();
        if (log) *log << "compressing the composite to BC6H..." << std::flush;
        compressComposite(asset); // about a second a 256^2 cube, no progress of its own
        if (log)
            *log << " " << secondsSince(compressStart) << " s (distance "
                 << (asset.halfCompositeDistance ? "R16F" : "R32F") << ")\n";
    }
    asset.inputs = cookedProbeInputs(scene, cookSettingsToJson(o.flavour), asset.centre);
    writeDistanceProbe(asset, o.out, scene.path);
    if (log) *log << planLine;
    result.asset = std::move(asset);
}

void cookWith(ProbeScene& scene, const CookOptions& o, const LightFieldCookSettings& s,
              CookResult& result, std::ostream* log) {
    const auto start = Clock::now();
    LightFieldBakeOptions b = lightFieldBakeOptions(scene, o, s);
    b.blocks = o.lightFieldBlocks;
    LightFieldAsset asset = bakeShared(o, "baking light field", b, result, log, [&] {
        return bakeLightFieldProbe(scene.registry, scene.markup, b);
    });
    result.bakeSeconds = secondsSince(start);
    // A cooked folder's bytes depend on its inputs only (a sharded bake merges to the same
    // bytes, shard_bake.h): the time is the result's, not the manifest's.
    asset.bakeSeconds = 0.0;
    asset.inputs = cookedProbeInputs(scene, cookSettingsToJson(o.flavour), asset.cellCentre);
    writeLightFieldProbe(asset, o.out, scene.path);
    result.cellCentre = b.cellCentre;
    result.cellSize = b.cellSize;
    result.overhangs =
        findReflectorOverhangs(scene.registry, scene.markup, b.cellCentre, b.cellSize);
    result.asset = std::move(asset);
}

void cookWith(ProbeScene& scene, const CookOptions& o, const PemCookSettings& s, CookResult& result,
              std::ostream* log) {
    validatePemCookSettings(s, scene.path); // before the progress bar: nothing to show
    const auto start = Clock::now();
    PemCookHooks b;
    b.centre = o.probeCentre;
    b.fits = &result.pemFits;
    PemAsset asset =
        bakeShared(o, "inferring PEMs", b, result, log, [&] { return cookPemAsset(scene, s, b); });
    result.bakeSeconds = secondsSince(start);
    if (s.compression == "bc6h") {
        const auto compressStart = Clock::now();
        if (log) *log << "compressing the maps to BC6H..." << std::flush;
        compressPemMaps(asset);
        if (log) *log << " " << secondsSince(compressStart) << " s\n";
    }
    asset.inputs = cookedProbeInputs(scene, cookSettingsToJson(o.flavour), asset.centre);
    writePemProbe(asset, o.out, scene.path);
    result.asset = std::move(asset);
}

CookResult cookPrepared(ProbeScene& scene, const CookOptions& o, std::ostream* log) {
    CookResult result;
    // One cookWith overload per flavour's settings: a flavour adds its overload, no branch.
    std::visit([&](const auto& settings) { cookWith(scene, o, settings, result, log); }, o.flavour);
    result.manifest = (std::filesystem::path(o.out) / "manifest.json").string();
    return result;
}

} // namespace

LightFieldBakeOptions lightFieldBakeOptions(const ProbeScene& scene, const CookOptions& o,
                                            const LightFieldCookSettings& s) {
    LightFieldBakeOptions b;
    b.cellCentre = s.cellCentre    ? *s.cellCentre
                   : o.probeCentre ? *o.probeCentre
                                   : markupProbeCentre(scene.registry, scene.markup, scene.loaded);
    b.cellSize = s.cellSize ? *s.cellSize : o.cellSize.value_or(markupCellSize(scene.markup));
    b.cameras = s.cameras;
    b.res = s.imageRes;
    b.compression = s.compression;
    b.sky = scene.sky.empty() ? nullptr : &scene.sky;
    return b;
}

CookResult cookProbe(const CookOptions& options, std::ostream* log) {
    prepareOutput(options, log);
    ProbeScene scene(options.scene, options.sky);
    throwIfCancelled(options.out);
    return cookPrepared(scene, options, log);
}

CookResult cookProbe(ProbeScene& scene, const CookOptions& options, std::ostream* log) {
    CookOptions o = options;
    o.scene = scene.path;
    prepareOutput(o, log);
    return cookPrepared(scene, o, log);
}

ProbeInputs cookedProbeInputs(const ProbeScene& scene, const nlohmann::json& settings,
                              glm::vec3 centre) {
    const nlohmann::json options = {{"settings", settings}, {"centre", vec3Json(centre)}};
    return sceneProbeInputs(scene, options.dump());
}

std::vector<std::string> cookFlavourNames() {
    std::vector<std::string> names;
    forEachCookFlavour(
        [&](const auto& s) { names.push_back(std::decay_t<decltype(s)>::kFlavour); });
    return names;
}

std::string cookFlavourList() {
    const std::vector<std::string> names = cookFlavourNames();
    std::string out;
    for (std::size_t i = 0; i < names.size(); ++i)
        out += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return out;
}

} // namespace specula
