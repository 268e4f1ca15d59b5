#pragma once
// The error budget a measured plan must meet: a PSNR floor ("32dB") or an RMSE ceiling
// ("rmse:0.03") over reflector rays. A setting's type (settings/setting.h): the distance
// flavour's --max-error, and the probe node's "max_error" (plan/plan_budget.h).
#include <string>

namespace specula {

struct ErrorBudget {
    enum class Kind { None, Psnr, Rmse };
    Kind kind = Kind::None;
    double value = 0.0; // dB for Psnr, linear radiance for Rmse
    std::string source; // where it came from ("--max-error", "<node> specula_probe.max_error")

    bool met(double psnr, double rmse) const;
    std::string text() const; // "32.00 dB", "rmse 0.0300", "none"
};

// "32dB", "32 dB", "32" (dB), "psnr:32", "rmse:0.03". Throws Error(file, field, ...) when
// unparsable, not finite or not positive.
ErrorBudget parseErrorBudget(const std::string& text, const std::string& file,
                             const std::string& field);

} // namespace specula
