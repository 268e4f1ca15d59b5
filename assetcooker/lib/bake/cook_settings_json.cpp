#include "assetcooker/lib/bake/cook_settings_json.h"

#include "components/reflection_probe/probe_volume.h"

#include <cmath>

namespace specula {

using nlohmann::json;

namespace {

// Every distance setting is listed here: the structured binding names them all, so a setting
// added to DistanceCookSettings stops this from compiling until it is carried (the measured
// plan's choice, seed and budgets were once left out, so a sharded bake planned under the
// defaults what the plain bake planned under the user's flags).
json settingsJson(const DistanceCookSettings& s) {
    const auto& [faceRes, planned, recordPlan, measuredPlan, maxError, maxMibPerProbe, planSeed,
                 glossy, prefilter, compression] = s;
    const GgxPrefilterOptions& p = prefilter;
    json budget = nullptr;
    if (maxError)
        budget = {{"kind", maxError->kind == ErrorBudget::Kind::Psnr ? "psnr" : "rmse"},
                  {"value", maxError->value},
                  {"source", maxError->source}};
    return {{"flavour", "distance"},
            {"face_res", faceRes},
            {"planned", planned},
            {"record_plan", recordPlan},
            {"measured_plan", measuredPlan},
            {"max_error", budget},
            {"max_mib_per_probe", maxMibPerProbe ? json(*maxMibPerProbe) : json(nullptr)},
            {"plan_seed", planSeed},
            {"glossy", toString(glossy)},
            {"compression", compression == DistanceCompression::Bc6h ? "bc6h" : "none"},
            {"prefilter",
             {{"levels", p.levels},
              {"samples", p.samples},
              {"max_samples", p.maxSamples},
              {"lod_bias", p.lodBias},
              {"d_inf", std::isfinite(p.dInf) ? json(p.dInf) : json(nullptr)}}}};
}

// Every light-field setting, named by the binding as the distance ones are.
json settingsJson(const LightFieldCookSettings& s) {
    const auto& [cellCentre, cellSize, cameras, imageRes, compression] = s;
    json j = {{"flavour", "lightfield"},
              {"cameras", cameras},
              {"image_res", imageRes},
              {"compression", compression == LightFieldCompression::BC1 ? "bc1" : "none"},
              {"cell_centre", nullptr},
              {"cell_size", nullptr}};
    if (cellCentre) j["cell_centre"] = {cellCentre->x, cellCentre->y, cellCentre->z};
    if (cellSize) j["cell_size"] = *cellSize;
    return j;
}

// Every PEM setting under its field name, for the writer and the reader alike: the
// structured binding names them all, so a setting added to PemCookSettings stops this from
// compiling until it is listed (a setting left out would bake shards under the defaults).
template <class S, class F> void pemSettingFields(S& s, F&& f) {
    auto& [samples, faceRes, supersample, regularisation, geometry, priorWeight, parameter, path,
           imageWidth, imageHeight, localLayer, localFaceRes, localSphere, mipLevels, rows,
           nonNegative, roundingReach, compression] = s;
    f("samples", samples), f("face_res", faceRes), f("supersample", supersample);
    f("regularisation", regularisation), f("geometry", geometry), f("prior_weight", priorWeight);
    f("parameter", parameter), f("path", path), f("image_width", imageWidth);
    f("image_height", imageHeight), f("local_layer", localLayer);
    f("local_face_res", localFaceRes), f("local_sphere", localSphere);
    f("mip_levels", mipLevels), f("rows", rows);
    f("non_negative", nonNegative), f("rounding_reach", roundingReach);
    f("compression", compression);
}

json settingsJson(const PemCookSettings& s) {
    json j = {{"flavour", "pem"}};
    pemSettingFields(s, [&](const char* name, const auto& v) { j[name] = v; });
    return j;
}

} // namespace

json cookSettingsToJson(const CookFlavour& flavour) {
    return std::visit([](const auto& s) { return settingsJson(s); }, flavour);
}

CookFlavour cookSettingsFromJson(const json& j, const std::string& file) {
    const std::string flavour = jsonMember<std::string>(j, "flavour", file, "settings.");
    if (flavour == "distance") {
        DistanceCookSettings s;
        s.faceRes = jsonMember<int>(j, "face_res", file, "settings.");
        s.planned = jsonMember<bool>(j, "planned", file, "settings.");
        s.recordPlan = jsonMember<bool>(j, "record_plan", file, "settings.");
        // A shard list from before these were carried planned under the defaults.
        if (j.contains("measured_plan"))
            s.measuredPlan = jsonMember<bool>(j, "measured_plan", file, "settings.");
        if (j.contains("plan_seed"))
            s.planSeed = jsonMember<std::uint32_t>(j, "plan_seed", file, "settings.");
        if (j.contains("max_error") && !j["max_error"].is_null()) {
            const json& b = j["max_error"];
            const std::string kind =
                jsonMember<std::string>(b, "kind", file, "settings.max_error.");
            if (kind != "psnr" && kind != "rmse")
                throw Error(file, "settings.max_error.kind", "expected psnr or rmse");
            ErrorBudget budget;
            budget.kind = kind == "psnr" ? ErrorBudget::Kind::Psnr : ErrorBudget::Kind::Rmse;
            budget.value = jsonMember<double>(b, "value", file, "settings.max_error.");
            budget.source = jsonMember<std::string>(b, "source", file, "settings.max_error.");
            if (!(budget.value > 0.0) || !std::isfinite(budget.value))
                throw Error(file, "settings.max_error.value", "expected a positive number");
            s.maxError = budget;
        }
        if (j.contains("max_mib_per_probe") && !j["max_mib_per_probe"].is_null())
            s.maxMibPerProbe = jsonMember<double>(j, "max_mib_per_probe", file, "settings.");
        const std::string glossy = jsonMember<std::string>(j, "glossy", file, "settings.");
        s.glossy = glossy == "on"    ? GlossyBake::On
                   : glossy == "off" ? GlossyBake::Off
                                     : GlossyBake::Auto;
        // Shard lists from before --compress bc6h hold no compression: none.
        if (j.contains("compression")) {
            const std::string c = jsonMember<std::string>(j, "compression", file, "settings.");
            if (c != "bc6h" && c != "none")
                throw Error(file, "settings.compression", "expected none or bc6h, got " + c);
            s.compression = c == "bc6h" ? DistanceCompression::Bc6h : DistanceCompression::None;
        }
        if (!j.contains("prefilter") || !j["prefilter"].is_object())
            throw Error(file, "settings.prefilter", "expected an object");
        const json& p = j["prefilter"];
        s.prefilter.levels = jsonMember<int>(p, "levels", file, "settings.prefilter.");
        s.prefilter.samples = jsonMember<int>(p, "samples", file, "settings.prefilter.");
        s.prefilter.maxSamples = jsonMember<int>(p, "max_samples", file, "settings.prefilter.");
        s.prefilter.lodBias = jsonMember<float>(p, "lod_bias", file, "settings.prefilter.");
        if (p.contains("d_inf") && !p["d_inf"].is_null())
            s.prefilter.dInf = jsonMember<float>(p, "d_inf", file, "settings.prefilter.");
        return s;
    }
    if (flavour == "lightfield") {
        LightFieldCookSettings s;
        s.cameras = jsonMember<int>(j, "cameras", file, "settings.");
        s.imageRes = jsonMember<int>(j, "image_res", file, "settings.");
        s.compression = jsonMember<std::string>(j, "compression", file, "settings.") == "bc1"
                            ? LightFieldCompression::BC1
                            : LightFieldCompression::None;
        if (j.contains("cell_centre") && !j["cell_centre"].is_null())
            s.cellCentre = probeVec3(j["cell_centre"], file, "settings.cell_centre");
        if (j.contains("cell_size") && !j["cell_size"].is_null())
            s.cellSize = jsonMember<float>(j, "cell_size", file, "settings.");
        return s;
    }
    if (flavour == "pem") {
        PemCookSettings s;
        pemSettingFields(s, [&](const char* name, auto& v) {
            // Shard lists from before --compress bc6h for PEM hold no compression: none.
            if (std::string_view(name) == "compression" && !j.contains(name)) return;
            v = jsonMember<std::decay_t<decltype(v)>>(j, name, file, "settings.");
        });
        validatePemCookSettings(s, file);
        return s;
    }
    throw Error(file, "settings.flavour",
                "expected distance, lightfield or pem, got '" + flavour + "'");
}

} // namespace specula
