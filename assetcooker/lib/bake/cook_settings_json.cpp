#include "assetcooker/lib/bake/cook_settings_json.h"

#include <optional>

namespace specula {

using nlohmann::json;

// Every setting each flavour declares (visitSettings) under its key, and the flavour's name:
// a setting added to a flavour is carried (and checksummed) without an edit here.
json cookSettingsToJson(const CookFlavour& flavour) {
    return std::visit(
        [](const auto& s) {
            json j = settingsToJson(s);
            j["flavour"] = std::decay_t<decltype(s)>::kFlavour;
            return j;
        },
        flavour);
}

CookFlavour cookSettingsFromJson(const json& j, const std::string& file) {
    const std::string name = jsonMember<std::string>(j, "flavour", file, "settings.");
    std::optional<CookFlavour> out;
    forEachCookFlavour([&](const auto& defaults) {
        using S = std::decay_t<decltype(defaults)>;
        if (name != S::kFlavour) return;
        S s = defaults;
        settingsFromJson(j, s, file, "settings.");
        checkCookSettings(s, file);
        out = s;
    });
    if (!out)
        throw Error(file, "settings.flavour",
                    "expected " + cookFlavourList() + ", got '" + name + "'");
    return *out;
}

} // namespace specula
