#pragma once
// The distance-cubemap flavour's cooking settings, each declared once (settings/setting.h):
// the bake's flags, the shard list's JSON and the level's options checksum all come from
// visitSettings below.
#include "assetcooker/lib/settings/error_budget.h"
#include "assetcooker/lib/settings/setting.h"
#include "components/reflection_probe/distance/distance_probe_asset.h"
#include "engine/image/ggx_prefilter.h"

#include <cstdint>
#include <optional>
#include <type_traits>

namespace specula {

// Whether a distance bake writes the composite's GGX prefiltered chain (glossy levels) for
// glossy reflectors. Auto: when some reflector of the scene has a roughness > 0.
enum class GlossyBake { Auto, On, Off };
const char* toString(GlossyBake g); // "auto", "on", "off"

struct DistanceCookSettings {
    static constexpr const char* kFlavour = "distance";
    int faceRes = 256;
    // true: the layers and methods of the effect plan; false: one layer per object. The plan
    // is recorded in the manifest either way when `recordPlan`.
    bool planned = true;
    bool recordPlan = true;
    // Planned: measured (the candidate configurations scored against Embree, the cheapest
    // meeting the budget; plan_measure.h) or analytic (effect_plan.h's thresholds alone).
    bool measuredPlan = true;
    // The measured plan's error budget (--max-error); unset: the probe node's max_error.
    std::optional<ErrorBudget> maxError;
    // The measured plan's memory budget (--max-mib-per-probe, MeasuredPlanOptions); unset: none.
    std::optional<double> maxMibPerProbe;
    std::uint32_t planSeed = 1;
    GlossyBake glossy = GlossyBake::Auto;
    // The chain when glossy (its levels, level 0 included: the default 6 writes 5 glossy
    // levels, the chain a glossy lookup builds itself when an asset has none).
    GgxPrefilterOptions prefilter;
    // --compress bc6h: the composite stored compressed (distance_compression.h).
    DistanceCompression compression = DistanceCompression::None;
};

template <class S, class V>
requires std::is_same_v<std::remove_const_t<S>, GgxPrefilterOptions>
void visitSettings(S& p, V&& visit) {
    visit({.key = "levels", .lo = 1}, p.levels);
    visit({.key = "samples", .lo = 1}, p.samples);
    visit({.key = "max_samples", .lo = 1}, p.maxSamples);
    visit({.key = "lod_bias"}, p.lodBias);
    visit({.key = "d_inf", .optional = true}, p.dInf);
}

template <class S, class V>
requires std::is_same_v<std::remove_const_t<S>, DistanceCookSettings>
void visitSettings(S& s, V&& visit) {
    visit({.key = "face_res",
           .flag = "--face-res",
           .help = "cube face resolution",
           .lo = 1,
           .hi = 4096},
          s.faceRes);
    visit({.key = "planned",
           .flag = "--layers",
           .help = "plan: the layers and methods of the effect plan (specula-cook plan); "
                   "objects: one layer per object",
           .words = {"objects", "plan"}},
          s.planned);
    visit({.key = "record_plan"}, s.recordPlan);
    visit({.key = "measured_plan",
           .flag = "--plan",
           .help = "with --layers plan: measured (candidates scored against Embree, the "
                   "cheapest meeting --max-error; it may bake at half --face-res) or analytic "
                   "(thresholds)",
           .words = {"analytic", "measured"},
           .optional = true},
          s.measuredPlan);
    visit({.key = "max_error",
           .flag = "--max-error",
           .help = "measured plan's budget over reflector rays: a PSNR (\"32dB\") or an RMSE "
                   "(\"rmse:0.03\"); default: the probe node's max_error",
           .optional = true},
          s.maxError);
    visit({.key = "max_mib_per_probe",
           .flag = "--max-mib-per-probe",
           .help = "measured plan: the most MiB a probe's textures may take on the GPU (cube "
                   "maps and sky); every candidate is also weighed with its composite in BC6H "
                   "(--compress bc6h), so the plan picks face size and format; candidates over "
                   "it are left out, and the smallest is used when none fits",
           .lo = 0.01,
           .hi = 1e6,
           .optional = true},
          s.maxMibPerProbe);
    visit({.key = "plan_seed", .optional = true}, s.planSeed);
    visit({.key = "glossy",
           .flag = "--glossy",
           .help = "the composite's GGX prefiltered chain for glossy reflectors (5 levels, "
                   "roughness 0.2 .. 1, layer_00_ggx_<i>.ktx2): auto when a reflector has "
                   "roughness > 0, on, off",
           .words = {"auto", "on", "off"}},
          s.glossy);
    visit({.key = "prefilter"}, s.prefilter);
    visit({.key = "compression",
           .flag = "--compress",
           .help = "none (RGBA float cubes) or bc6h (the composite's radiance in BC6H, its "
                   "distance R16F where halves hold it within the lookup's d_e, else R32F: "
                   "asset format 3.0)",
           .words = {"none", "bc6h"},
           .optional = true},
          s.compression);
}

// The measured plan's budget in the settings JSON: {"kind": "psnr"|"rmse", "value", "source"}.
template <> struct SettingJson<ErrorBudget> {
    static nlohmann::json write(const ErrorBudget& b, const SettingInfo&);
    static ErrorBudget read(const nlohmann::json& j, const SettingInfo&, const std::string& file,
                            const std::string& field);
};

// Refuses settings no bake can run (none for this flavour beyond each field's own check).
inline void checkCookSettings(const DistanceCookSettings&, const std::string&) {}

} // namespace specula
