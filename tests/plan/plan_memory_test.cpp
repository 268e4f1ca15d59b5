// The measured plan's memory budget (issue 36, --max-mib-per-probe): a candidate whose textures
// take more is left out of the choice, even the best PSNR; the reason names the budget; when
// none fits, the smallest is used and a warning says so. And every distance setting of a bake,
// the plan's choice, seed and budgets included, reaches a farm's shards and comes back.
#include "assetcooker/lib/plan/plan_candidates.h"
#include "assetcooker/lib/bake/cook_settings_json.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace specula;

namespace {

PlanCandidate candidate(const char* method, int faceRes, double psnr, double mib, double cost) {
    PlanCandidate c;
    c.method = method;
    c.faceRes = faceRes;
    c.psnr = psnr;
    c.rmse = std::pow(10.0, -psnr / 20.0);
    c.mib = mib;
    c.cost = cost;
    return c;
}

const std::vector<PlanCandidate> kCandidates = {
    candidate("secant", 256, 31.3, 24.0, 3.0), // best and cheapest, 24 MiB
    candidate("secant", 128, 30.1, 6.0, 3.0),  // 1.2 dB less, a quarter of the memory
    candidate("envmap", 128, 22.0, 6.0, 1.0),  // cheapest of all, far below
};

} // namespace

TEST(PlanMemory, ACandidateOverTheBudgetIsLeftOutWhateverItsPsnr) {
    std::string reason, warning;
    std::vector<PlanCandidate> free = kCandidates;
    EXPECT_EQ(choosePlanCandidate(free, ErrorBudget{}, reason, warning), 0) << reason;

    std::vector<PlanCandidate> capped = kCandidates;
    EXPECT_EQ(choosePlanCandidate(capped, ErrorBudget{}, reason, warning, 8.0), 1) << reason;
    EXPECT_FALSE(capped[0].meets); // over 8 MiB: neither meets nor sets the best PSNR
    EXPECT_TRUE(capped[1].meets);  // so 128^2 is the best, and within its own slack
    EXPECT_NE(reason.find("in at most 8.0 MiB per probe"), std::string::npos) << reason;
    EXPECT_TRUE(warning.empty()) << warning;
}

TEST(PlanMemory, WhenNothingFitsTheSmallestIsUsedAndSaid) {
    std::string reason, warning;
    std::vector<PlanCandidate> cs = kCandidates;
    // Both 128^2 candidates take 6 MiB: the better picture of the two wins the tie.
    EXPECT_EQ(choosePlanCandidate(cs, ErrorBudget{}, reason, warning, 2.0), 1) << reason;
    EXPECT_NE(warning.find("no candidate fits --max-mib-per-probe 2.0 MiB"), std::string::npos)
        << warning;
    EXPECT_NE(warning.find("secant 128^2 at 6.0 MiB"), std::string::npos) << warning;
    for (const PlanCandidate& c : cs)
        EXPECT_FALSE(c.meets);
}

TEST(PlanMemory, EveryDistanceSettingReachesTheShardsAndComesBack) {
    DistanceCookSettings s;
    s.faceRes = 96;
    s.planned = true;
    s.recordPlan = false;
    s.measuredPlan = false;
    s.maxError = parseErrorBudget("31.5dB", "", "--max-error");
    s.maxMibPerProbe = 12.5;
    s.planSeed = 7;
    s.glossy = GlossyBake::On;
    s.prefilter.levels = 4;
    s.compression = DistanceCompression::Bc6h;
    const DistanceCookSettings back =
        std::get<DistanceCookSettings>(cookSettingsFromJson(cookSettingsToJson(s), "shards.json"));
    EXPECT_EQ(back.faceRes, 96);
    EXPECT_FALSE(back.recordPlan);
    EXPECT_FALSE(back.measuredPlan);
    ASSERT_TRUE(back.maxError.has_value());
    EXPECT_EQ(back.maxError->kind, ErrorBudget::Kind::Psnr);
    EXPECT_DOUBLE_EQ(back.maxError->value, 31.5);
    EXPECT_EQ(back.maxError->source, "--max-error");
    ASSERT_TRUE(back.maxMibPerProbe.has_value());
    EXPECT_DOUBLE_EQ(*back.maxMibPerProbe, 12.5);
    EXPECT_EQ(back.planSeed, 7u);
    EXPECT_EQ(back.glossy, GlossyBake::On);
    EXPECT_EQ(back.prefilter.levels, 4);
    EXPECT_EQ(back.compression, DistanceCompression::Bc6h);
    // Unset budgets stay unset.
    const DistanceCookSettings plain = std::get<DistanceCookSettings>(
        cookSettingsFromJson(cookSettingsToJson(DistanceCookSettings{}), "shards.json"));
    EXPECT_FALSE(plain.maxError.has_value());
    EXPECT_FALSE(plain.maxMibPerProbe.has_value());
    EXPECT_TRUE(plain.measuredPlan);
    EXPECT_EQ(plain.compression, DistanceCompression::None);
}

// The format as a candidate: a BC6H twin that fits where its float self does not wins over a
// smaller float resolution with less PSNR, and the reason names both formats' figures.
TEST(PlanMemory, TheBudgetPicksTheFormatAndTheReasonNamesTheOther) {
    std::vector<PlanCandidate> cs = kCandidates;
    applyPlanFormats(cs, PlanFormats::FloatAndBc6h);
    ASSERT_EQ(cs.size(), 6u);
    cs[1].psnr = 31.2, cs[1].mib = 4.5; // secant 256^2 bc6h
    cs[3].psnr = 30.0, cs[3].mib = 1.2; // secant 128^2 bc6h
    cs[5].psnr = 21.9, cs[5].mib = 1.2; // envmap 128^2 bc6h
    EXPECT_EQ(cs[1].label(), "secant 256^2 bc6h");
    std::string reason, warning;
    std::vector<PlanCandidate> capped = cs;
    EXPECT_EQ(choosePlanCandidate(capped, ErrorBudget{}, reason, warning, 8.0), 1) << reason;
    EXPECT_NE(reason.find("stored BC6H (4.5 MiB, 31.20 dB): float takes 24.0 MiB"),
              std::string::npos)
        << reason;
    // With room for float, float wins the better picture at the same cost.
    std::vector<PlanCandidate> roomy = cs;
    EXPECT_EQ(choosePlanCandidate(roomy, ErrorBudget{}, reason, warning, 32.0), 0) << reason;
    EXPECT_NE(reason.find("stored float (24.0 MiB, 31.30 dB): BC6H reaches 31.20 dB in 4.5 MiB"),
              std::string::npos)
        << reason;
    // BC6H alone: every candidate compressed.
    std::vector<PlanCandidate> only = kCandidates;
    applyPlanFormats(only, PlanFormats::Bc6h);
    ASSERT_EQ(only.size(), 3u);
    for (const PlanCandidate& c : only)
        EXPECT_TRUE(c.compressed);
}
