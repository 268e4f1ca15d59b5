// The error budget's figure and tables: error_budget.png, bench.csv's budget columns and
// bench.md's budget table (declared in error_budget.h).
#include "sandbox/lib/flavours/distance/error_budget.h"

#include "engine/image/plot_canvas.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace specula {

namespace {

std::string fmt(double v, const char* f = "%.6g") {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

// dB gained by an experiment: 10 log10(base / experiment).
double gainDb(double base, double experiment) {
    return 10.0 * std::log10(base / experiment);
}

struct Segment {
    const char* name;
    PlotColour colour;
};
constexpr std::array<Segment, 5> kSegments = {{
    {"search (a)", {0.95f, 0.55f, 0.10f}},
    {"resolution (b)", {0.25f, 0.55f, 0.95f}},
    {"silhouettes (c)", {0.20f, 0.80f, 0.35f}},
    {"disocclusion (d)", {0.75f, 0.35f, 0.90f}},
    {"residual", {0.50f, 0.50f, 0.52f}},
}};

std::array<double, 5> shares(const MethodErrorBudget& b) {
    auto pos = [&](double t) {
        return std::isnan(t) || b.base <= 0 ? 0.0 : std::max(t, 0.0) / b.base;
    };
    return {pos(b.termSearch()), pos(b.termResolution()), pos(b.termSilhouettes()),
            pos(b.termDisocclusion()), b.base > 0 ? b.residual / b.base : 0.0};
}

void drawPanel(PlotCanvas& cv, int ox, int pw, int ph, const std::string& scene,
               const std::vector<const MethodErrorBudget*>& bars) {
    using OIIO::ImageBufAlgo::TextAlignX;
    const PlotColour axis{0.8f, 0.8f, 0.8f}, grid{0.07f, 0.07f, 0.08f}, white{1.f, 1.f, 1.f};
    const int left = ox + 64, right = ox + pw - 150, top = 58, bottom = ph - 70;
    double yMax = 1.25;
    for (const MethodErrorBudget* b : bars) {
        const std::array<double, 5> s = shares(*b);
        double sum = 0;
        for (double v : s)
            sum += v;
        yMax = std::max(yMax, sum * 1.08);
    }
    auto Y = [&](double v) { return int(bottom - v / yMax * (bottom - top)); };
    for (double v = 0; v <= yMax + 1e-9; v += 0.25) {
        cv.line(left, Y(v), right, Y(v), grid);
        cv.line(left - 5, Y(v), left, Y(v), axis);
        cv.text(left - 8, Y(v) + 5, plotNumber("%.2f", v), 13, axis, TextAlignX::Right);
    }
    cv.box(left, top, right, bottom, axis, false);
    cv.text(ox + 14, top - 10, "share of the baseline MSE (twin, reflector rays)", 13, axis);
    cv.text((left + right) / 2, 24, "error budget: " + scene, 17, white, TextAlignX::Center);
    const int n = std::max<int>(1, int(bars.size()));
    const int slot = (right - left) / n, width = std::max(6, slot * 3 / 5);
    for (int i = 0; i < int(bars.size()); ++i) {
        const MethodErrorBudget& b = *bars[std::size_t(i)];
        const int cx = left + slot * i + slot / 2, x0 = cx - width / 2, x1 = cx + width / 2;
        double acc = 0;
        const std::array<double, 5> s = shares(b);
        for (std::size_t k = 0; k < s.size(); ++k) {
            if (s[k] <= 0) continue;
            cv.box(x0, Y(acc + s[k]), x1, Y(acc), kSegments[k].colour, true);
            acc += s[k];
        }
        cv.line(x0 - 4, Y(1.0), x1 + 4, Y(1.0), white); // the baseline
        cv.text(cx, Y(std::max(acc, 1.0)) - 6, fmt(psnrOfMse(b.base), "%.1f") + " dB", 11, axis,
                TextAlignX::Center);
        cv.text(cx, bottom + 18, b.method, 12, axis, TextAlignX::Center);
        cv.text(cx, bottom + 34, b.params, 11, axis, TextAlignX::Center);
    }
    int ly = top + 20;
    for (const Segment& s : kSegments) {
        cv.box(right + 12, ly - 10, right + 24, ly + 2, s.colour, true);
        cv.text(right + 30, ly, s.name, 12, axis);
        ly += 18;
    }
    cv.line(right + 10, ly - 4, right + 26, ly - 4, white);
    cv.text(right + 30, ly, "baseline", 12, axis);
}

} // namespace

Image errorBudgetPlot(const std::vector<MethodErrorBudget>& budgets,
                      const std::vector<std::string>& scenes, int pw, int ph) {
    std::vector<std::string> drawn;
    for (const std::string& s : scenes)
        if (std::any_of(budgets.begin(), budgets.end(),
                        [&](const MethodErrorBudget& b) { return b.scene == s; }))
            drawn.push_back(s);
    PlotCanvas cv(pw * std::max<int>(1, int(drawn.size())), ph);
    for (int i = 0; i < int(drawn.size()); ++i) {
        std::vector<const MethodErrorBudget*> bars;
        for (const MethodErrorBudget& b : budgets)
            if (b.scene == drawn[std::size_t(i)]) bars.push_back(&b);
        drawPanel(cv, i * pw, pw, ph, drawn[std::size_t(i)], bars);
    }
    return cv.image();
}

std::string errorBudgetCsvHeader() {
    return ",budget_rays,budget_mse_base,budget_mse_exact_search,budget_mse_res2x,"
           "budget_mse_same_surface,budget_mse_seen,budget_mse_all,budget_mse_oracle,"
           "budget_hidden_share,budget_term_search,budget_term_resolution,"
           "budget_term_silhouettes,budget_term_disocclusion,budget_interaction,"
           "budget_dominant,budget_gpu_mse,budget_mse_residual,budget_residual_set,budget_mse_half,"
           "budget_mse_bc6h,budget_bytes_rgba32f,budget_bytes_rgba16f,budget_bytes_bc6h";
}

std::string errorBudgetCsvValues(const MethodErrorBudget* b) {
    if (!b) {
        // A row without a budget: no empty field (a reader that splits on commas may drop a
        // trailing one), 0 rays, NaN figures, "-" for the names.
        std::string row = ",0";
        for (int i = 0; i < 13; ++i)
            row += ",nan";
        // dominant, GPU MSE, residual, its set, half, bc6h, the three byte counts
        return row + ",-,nan,nan,-,nan,nan,0,0,0";
    }
    std::ostringstream s;
    s << ',' << b->rays;
    for (double v : {b->base, b->exact, b->res2x, b->sameSurface, b->seen, b->all, b->oracle,
                     b->hiddenShare, b->termSearch(), b->termResolution(), b->termSilhouettes(),
                     b->termDisocclusion(), b->interaction()})
        s << ',' << fmt(v);
    s << ',' << b->dominant() << ',' << fmt(b->gpuMse) << ',' << fmt(b->residual) << ','
      << b->residualSet << ',' << fmt(b->halfFloat) << ',' << fmt(b->bc6h) << ',' << b->bytesFloat
      << ',' << b->bytesHalf << ',' << b->bytesBc6h;
    return s.str();
}

namespace {

// A storage experiment's PSNR change in dB against the baseline ((e), (f)); "-" when not
// measured, and 0 when both MSEs are equal (two infinite PSNRs, an exact probe, differ by
// nothing rather than by NaN).
std::string mib(std::size_t bytes) {
    return fmt(double(bytes) / (1024.0 * 1024.0), "%.2f");
}

std::string storageChange(double mse, double base) {
    if (std::isnan(mse)) return "-";
    if (mse == base) return "+0.000";
    const double change = psnrOfMse(mse) - psnrOfMse(base);
    return std::isnan(change) ? "-" : fmt(change, "%+.3f");
}

} // namespace

std::string errorBudgetMarkdown(const std::vector<MethodErrorBudget>& budgets,
                                const std::string& scene) {
    std::ostringstream s;
    bool any = false;
    for (const MethodErrorBudget& b : budgets) {
        if (b.scene != scene) continue;
        if (!any)
            s << "Error budget (CPU twin over the truth's reflector rays; MSE x 1e3, each "
                 "experiment's gain in dB in brackets):\n\n"
              << "| method | params | base (dB) | GPU dB | search (a) | resolution (b) | "
                 "silhouettes (c) | disocclusion (d) | residual (set) | all four | interaction | "
                 "oracle | "
                 "hidden % | dominant | RGBA16F dB (e) | BC6H dB (f) | MiB f32 / f16 / BC6H |\n"
              << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---"
                 ":|"
                 "\n";
        any = true;
        auto term = [&](double t, double experiment) {
            if (std::isnan(t)) return std::string("-");
            return fmt(1e3 * t, "%.3f") + " (" + fmt(gainDb(b.base, experiment), "%+.2f") + ")";
        };
        s << "| " << b.method << " | " << b.params << " | " << fmt(1e3 * b.base, "%.3f") << " ("
          << fmt(psnrOfMse(b.base), "%.2f") << ") | " << fmt(psnrOfMse(b.gpuMse), "%.2f") << " | "
          << term(b.termSearch(), b.exact) << " | " << term(b.termResolution(), b.res2x) << " | "
          << term(b.termSilhouettes(), b.sameSurface) << " | " << term(b.termDisocclusion(), b.seen)
          << " | " << fmt(1e3 * b.residual, "%.3f") << " (" << b.residualSet << ") | "
          << fmt(1e3 * b.all, "%.3f") << " | " << fmt(1e3 * b.interaction(), "%.3f") << " | "
          << fmt(1e3 * b.oracle, "%.3f") << " (" << fmt(psnrOfMse(b.oracle), "%.2f") << ") | "
          << fmt(100 * b.hiddenShare, "%.1f") << " | " << b.dominant() << " | "
          << storageChange(b.halfFloat, b.base) << " | " << storageChange(b.bc6h, b.base) << " | "
          << mib(b.bytesFloat) << " / " << mib(b.bytesHalf) << " / " << mib(b.bytesBc6h) << " |\n";
    }
    for (const MethodErrorBudget& b : budgets)
        if (b.scene == scene && !b.res2xNote.empty()) {
            s << "\nresolution (b) not measured: " << b.res2xNote << "\n";
            break;
        }
    if (any) s << "\n";
    return s.str();
}

} // namespace specula
