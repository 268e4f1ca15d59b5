#include "assetcooker/lib/flavours/distance/distance_cook_settings.h"

namespace specula {

const char* toString(GlossyBake g) {
    switch (g) {
    case GlossyBake::On:
        return "on";
    case GlossyBake::Off:
        return "off";
    case GlossyBake::Auto:
        break;
    }
    return "auto";
}

nlohmann::json SettingJson<ErrorBudget>::write(const ErrorBudget& b, const SettingInfo&) {
    return {{"kind", b.kind == ErrorBudget::Kind::Psnr ? "psnr" : "rmse"},
            {"value", b.value},
            {"source", b.source}};
}

ErrorBudget SettingJson<ErrorBudget>::read(const nlohmann::json& j, const SettingInfo&,
                                           const std::string& file, const std::string& field) {
    if (!j.is_object()) throw Error(file, field, "expected an object");
    const SettingInfo kind{.words = {"psnr", "rmse"}};
    const auto member = [&](const char* name) -> const nlohmann::json& {
        if (!j.contains(name)) throw Error(file, field + "." + name, "missing from the shard list");
        return j.at(name);
    };
    ErrorBudget b;
    b.kind = SettingJson<std::string>::read(member("kind"), kind, file, field + ".kind") == "psnr"
                 ? ErrorBudget::Kind::Psnr
                 : ErrorBudget::Kind::Rmse;
    b.value = SettingJson<double>::read(member("value"), {}, file, field + ".value");
    if (!(b.value > 0.0) || !std::isfinite(b.value))
        throw Error(file, field + ".value", "expected a positive number");
    b.source = SettingJson<std::string>::read(member("source"), {}, file, field + ".source");
    return b;
}

} // namespace specula
