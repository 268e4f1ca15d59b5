// The error budget as `specula-sandbox bench` writes it: the budget_* columns of bench.csv
// for every distance method at d_e 0.01, the twin's baseline against the GPU row it
// decomposes, the table in bench.md and error_budget.png.
#include "support/csv_table.h"
#include "support/shell_tool.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using specula::test::CsvRow;
using specula::test::num;
using specula::test::readCsv;

TEST(ErrorBudgetBench, QuickBenchWritesTheBudget) {
    const specula::test::TempDir dir("budget-bench");
    const fs::path out = dir.path / "bench";
    const fs::path room = fs::path(SPECULA_SOURCE_DIR) / "assets/room/room.gltf";
    const specula::test::ToolRun r = specula::test::runShellTool(
        fs::path(SPECULA_BIN_DIR) / "specula-sandbox",
        "bench --quick --size 96x72 --face-res 32 --max-frames 4 --scene " +
            specula::test::shellQuote(room.string()) + " --out " +
            specula::test::shellQuote(out.string()));
    ASSERT_EQ(r.status, 0) << r.err;
    std::set<std::string> budgeted;
    for (const CsvRow& row : readCsv(out / "bench.csv")) {
        const std::string method = row.at("method"), params = row.at("params");
        if (num(row, "budget_rays") == 0) {
            EXPECT_EQ(row.at("budget_dominant"), "-");
            continue;
        }
        budgeted.insert(method);
        EXPECT_TRUE(params == "-" || params == "d_e=0.01") << method << " " << params;
        const double base = num(row, "budget_mse_base"), gpu = num(row, "budget_gpu_mse");
        EXPECT_TRUE(std::isfinite(base) && base > 0) << method;
        // The twin runs the shader's lookup over the truth's rays: its baseline is the GPU
        // row's error, up to the few pixels the rasteriser and the tracer place differently.
        EXPECT_NEAR(10 * std::log10(gpu / base), 0.0, 0.5) << method;
        EXPECT_NEAR(gpu, std::pow(num(row, "rmse"), 2.0), 1e-4 * gpu) << method;
        // Each term is the baseline less its experiment, as printed.
        EXPECT_NEAR(num(row, "budget_term_search"), base - num(row, "budget_mse_exact_search"),
                    1e-5 * base)
            << method;
        EXPECT_NEAR(num(row, "budget_term_disocclusion"), base - num(row, "budget_mse_seen"),
                    1e-5 * base)
            << method;
        // The residual is the least any combination leaves, the baseline included.
        EXPECT_LE(num(row, "budget_mse_residual"), base) << method;
        EXPECT_FALSE(row.at("budget_residual_set").empty()) << method;
        const double hidden = num(row, "budget_hidden_share");
        EXPECT_TRUE(hidden >= 0 && hidden <= 1) << method;
    }
    EXPECT_EQ(budgeted, (std::set<std::string>{"envmap", "boxproj", "bisection", "secant",
                                               "avgdist", "march", "layered"}));
    EXPECT_TRUE(fs::exists(out / "error_budget.png"));
    std::ifstream md(out / "bench.md");
    const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("Error budget"), std::string::npos);
}

} // namespace
