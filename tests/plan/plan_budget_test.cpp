// The measured plan's error budget as text and markup, its bad input, and the d_e a measured
// plan hands the runtime (the Planned method).
#include "assetcooker/lib/cli/cli.h"
#include "assetcooker/lib/plan/plan_budget.h"
#include "assetcooker/lib/plan/plan_candidates.h"
#include "components/reflection_probe/distance/distance_lookup_config.h"
#include "engine/core/error.h"
#include "plan/code_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

using namespace specula;

namespace {

// The Error's field, or "" when `f` throws none.
template <class F> std::string fieldThrown(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.field() + ": " + e.message();
    }
    return "";
}

SceneMarkup markupWith(const std::string& probeExtras) {
    test::CodeScene c;
    c.node("probe", glm::vec3(0.f), nullptr, probeExtras);
    updateWorldTransforms(c.reg);
    return readSceneMarkup(c.reg, c.scene, "budget.gltf");
}

} // namespace

TEST(PlanBudget, ParsesPsnrAndRmse) {
    const ErrorBudget a = parseErrorBudget("32dB", "", "--max-error");
    EXPECT_EQ(a.kind, ErrorBudget::Kind::Psnr);
    EXPECT_DOUBLE_EQ(a.value, 32.0);
    EXPECT_DOUBLE_EQ(parseErrorBudget(" 28.5 dB", "", "--max-error").value, 28.5);
    EXPECT_DOUBLE_EQ(parseErrorBudget("psnr:30", "", "--max-error").value, 30.0);
    const ErrorBudget r = parseErrorBudget("rmse:0.03", "", "--max-error");
    EXPECT_EQ(r.kind, ErrorBudget::Kind::Rmse);
    EXPECT_DOUBLE_EQ(r.value, 0.03);
    EXPECT_TRUE(a.met(32.0, 1.0));
    EXPECT_FALSE(a.met(31.99, 0.0));
    EXPECT_TRUE(r.met(0.0, 0.03));
    EXPECT_FALSE(r.met(99.0, 0.031));
}

TEST(PlanBudget, UnparsableOrNonPositiveNamesTheField) {
    for (const char* bad : {"", "fast", "32 dBm", "rmse:", "rmse:x", "nan", "inf dB"})
        EXPECT_EQ(
            fieldThrown([&] { parseErrorBudget(bad, "", "--max-error"); }).rfind("--max-error", 0),
            0u)
            << bad;
    for (const char* bad : {"0dB", "-3dB", "rmse:0", "rmse:-0.1"})
        EXPECT_EQ(
            fieldThrown([&] { parseErrorBudget(bad, "", "--max-error"); }).rfind("--max-error", 0),
            0u)
            << bad;
}

TEST(PlanBudget, MarkupMaxErrorOfTheWrongTypeNamesNodeAndField) {
    const ErrorBudget n =
        markupErrorBudget(markupWith("{\"specula_probe\": {\"max_error\": 31}}"), 0);
    EXPECT_EQ(n.kind, ErrorBudget::Kind::Psnr);
    EXPECT_DOUBLE_EQ(n.value, 31.0);
    const ErrorBudget s =
        markupErrorBudget(markupWith("{\"specula_probe\": {\"max_error\": \"rmse:0.02\"}}"), 0);
    EXPECT_EQ(s.kind, ErrorBudget::Kind::Rmse);
    EXPECT_EQ(markupErrorBudget(markupWith("{\"specula_probe\": {}}"), 0).kind,
              ErrorBudget::Kind::None);
    for (const char* bad : {"true", "[30]", "{\"db\": 30}", "\"loud\"", "-2", "0"}) {
        const SceneMarkup m =
            markupWith(std::string("{\"specula_probe\": {\"max_error\": ") + bad + "}}");
        try {
            markupErrorBudget(m, 0);
            ADD_FAILURE() << bad << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), "probe") << bad;
            EXPECT_EQ(e.field(), "specula_probe.max_error") << bad;
        }
    }
}

TEST(PlanBudget, CommandLineRefusesABadMaxErrorNamingTheFlag) {
    const std::string scene = std::string(SPECULA_SOURCE_DIR) + "/assets/room/room.gltf";
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"plan", scene, "--max-error", "fast"},
          std::vector<std::string>{"plan", scene, "--max-error", "-1dB"},
          std::vector<std::string>{"bake", scene, "--out", "/nonexistent/never", "--max-error",
                                   "rmse:0"}}) {
        std::ostringstream out, err;
        EXPECT_EQ(cook::runCli(args, out, err), 2) << args[3];
        EXPECT_NE(err.str().find("--max-error"), std::string::npos) << err.str();
    }
}

TEST(PlannedLookup, TakesTheMeasuredToleranceElseTheUsers) {
    DistanceProbeAsset a;
    a.manifestPath = "m.json";
    a.range = 10.f;
    a.dInf = 100.f;
    a.faceRes = 8;
    a.layers.resize(1);
    a.layers[0].method = "secant";
    DistanceProbe p;
    p.method = DistanceMethod::Planned;
    p.errorTolerance = 0.01f;
    EXPECT_FLOAT_EQ(makeLookupConfig(p, a).params.tolerance, 0.01f); // no plan: the user's
    a.effectPlan = "{\"mode\": {\"value\": \"single\"}}";
    EXPECT_FLOAT_EQ(makeLookupConfig(p, a).params.tolerance, 0.01f); // an analytic plan
    a.effectPlan = "{\"lookup\": {\"method\": \"secant\", \"tolerance\": 0.1}}";
    const DistanceLookupConfig c = makeLookupConfig(p, a);
    EXPECT_FLOAT_EQ(c.params.tolerance, 0.1f);
    EXPECT_EQ(c.params.maxSteps, bisectionSteps(c.params.range, 0.1f));
    p.method = DistanceMethod::Secant; // other methods keep the user's d_e
    EXPECT_FLOAT_EQ(makeLookupConfig(p, a).params.tolerance, 0.01f);
    p.method = DistanceMethod::Planned;
    for (const char* bad :
         {"{\"lookup\": {\"tolerance\": \"0.1\"}}", "{\"lookup\": {\"tolerance\": -1}}"}) {
        a.effectPlan = bad;
        EXPECT_EQ(
            fieldThrown([&] { makeLookupConfig(p, a); }).rfind("effect_plan.lookup.tolerance", 0),
            0u)
            << bad;
    }
    a.effectPlan = "not json";
    EXPECT_EQ(fieldThrown([&] { makeLookupConfig(p, a); }).rfind("effect_plan:", 0), 0u);
}

// Two candidates of equal predicted time, one with half the faces (less memory, 0.4 dB
// less): without a budget the better picture is chosen (the 0.5 dB slack trades accuracy
// for time, not memory), with a budget both meet the smaller one is.
TEST(PlanChoice, EqualTimeTradesMemoryOnlyUnderABudget) {
    auto candidate = [](int faceRes, double psnr, double mib) {
        PlanCandidate c;
        c.method = "layered";
        c.tolerance = 0.01f;
        c.faceRes = faceRes;
        c.psnr = psnr;
        c.rmse = std::pow(10.0, -psnr / 20.0);
        c.mib = mib;
        c.cost = 9.47;
        return c;
    };
    PlanCandidate slower = candidate(256, 31.35, 98.0);
    slower.method = "march";
    slower.cost = 12.0; // best PSNR, but slower: never the choice below
    const std::vector<PlanCandidate> cs = {candidate(256, 31.3, 98.0), candidate(128, 30.9, 30.5),
                                           slower};
    std::string reason, warning;

    std::vector<PlanCandidate> none = cs;
    EXPECT_EQ(choosePlanCandidate(none, ErrorBudget{}, reason, warning), 0) << reason;
    EXPECT_TRUE(none[0].meets && none[1].meets && none[2].meets);
    EXPECT_NE(reason.find("31.30 dB"), std::string::npos) << reason;

    std::vector<PlanCandidate> budgeted = cs;
    const ErrorBudget b = parseErrorBudget("30dB", "", "--max-error");
    EXPECT_EQ(choosePlanCandidate(budgeted, b, reason, warning), 1) << reason;
    EXPECT_NE(reason.find("30.5 MiB"), std::string::npos) << reason;
    EXPECT_TRUE(warning.empty());

    // The time still comes first: a cheaper candidate within the slack wins either way.
    std::vector<PlanCandidate> faster = cs;
    faster[1].cost = 9.0;
    EXPECT_EQ(choosePlanCandidate(faster, ErrorBudget{}, reason, warning), 1) << reason;
}
