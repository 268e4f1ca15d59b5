#include "assetcooker/lib/plan/plan_budget.h"

#include "engine/core/error.h"

#include <cmath>

namespace specula {

ErrorBudget markupErrorBudget(const SceneMarkup& markup, int markupProbe) {
    if (markupProbe < 0 || markupProbe >= int(markup.probes.size())) return {};
    const ProbeMarkup& p = markup.probes[std::size_t(markupProbe)];
    if (!p.options.is_object() || !p.options.contains("max_error")) return {};
    const nlohmann::json& v = p.options["max_error"];
    const std::string field = "specula_probe.max_error";
    ErrorBudget b;
    if (v.is_number()) {
        b.kind = ErrorBudget::Kind::Psnr;
        b.value = v.get<double>();
        if (!(b.value > 0.0) || !std::isfinite(b.value))
            throw Error(p.node, field, "a PSNR in dB must be positive and finite, got " + v.dump());
    } else if (v.is_string()) {
        b = parseErrorBudget(v.get<std::string>(), p.node, field);
    } else {
        throw Error(p.node, field,
                    "expected a string (\"32dB\", \"rmse:0.03\") or a number (dB), got " +
                        std::string(v.type_name()));
    }
    b.source = p.node + " " + field;
    return b;
}

} // namespace specula
