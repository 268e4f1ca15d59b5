#include "assetcooker/lib/settings/error_budget.h"

#include "engine/core/error.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace specula {

namespace {

std::string lower(std::string s) {
    for (char& c : s)
        c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return "";
    return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

// The whole of `s` as a number, or NaN.
double number(const std::string& s) {
    if (s.empty()) return std::nan("");
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    return end && *end == '\0' ? v : std::nan("");
}

} // namespace

bool ErrorBudget::met(double psnr, double rmse) const {
    switch (kind) {
    case Kind::Psnr:
        return psnr >= value;
    case Kind::Rmse:
        return rmse <= value;
    case Kind::None:
        break;
    }
    return true;
}

std::string ErrorBudget::text() const {
    char b[64];
    if (kind == Kind::Psnr)
        std::snprintf(b, sizeof b, "%.2f dB", value);
    else if (kind == Kind::Rmse)
        std::snprintf(b, sizeof b, "rmse %.4f", value);
    else
        return "none";
    return b;
}

ErrorBudget parseErrorBudget(const std::string& text, const std::string& file,
                             const std::string& field) {
    std::string s = lower(trim(text));
    ErrorBudget b;
    b.kind = ErrorBudget::Kind::Psnr;
    if (s.rfind("rmse:", 0) == 0) {
        b.kind = ErrorBudget::Kind::Rmse;
        s = trim(s.substr(5));
    } else if (s.rfind("psnr:", 0) == 0) {
        s = trim(s.substr(5));
    }
    if (b.kind == ErrorBudget::Kind::Psnr && s.size() > 2 && s.substr(s.size() - 2) == "db")
        s = trim(s.substr(0, s.size() - 2));
    b.value = number(s);
    if (!std::isfinite(b.value))
        throw Error(file, field,
                    "expected a PSNR (\"32dB\") or an RMSE (\"rmse:0.03\"), got '" + text + "'");
    if (!(b.value > 0.0))
        throw Error(file, field, "the budget must be positive, got '" + text + "'");
    b.source = field;
    return b;
}

} // namespace specula
