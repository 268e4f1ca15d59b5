// The blend of the two samples nearest the parameter on a closed path (the orbit): every
// sample's weight is a continuous function of the parameter, including across the wrap from
// parameter 1 back to 0, where an open path would jump from the last sample to the first.
#include "components/reflection_probe/pem/pem_blend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace specula {
namespace {

// Each sample's weight at `parameter`, as a vector over the samples.
std::vector<float> sampleWeights(const std::vector<float>& params, float parameter, bool periodic) {
    const PemBlendWeights w = pemBlend(params, parameter, false, periodic);
    std::vector<float> out(params.size(), 0.f);
    out[std::size_t(w.a)] += 1.f - w.wb;
    out[std::size_t(w.b)] += w.wb;
    return out;
}

// Largest change of any sample's weight between parameters `step` apart, walking the loop
// once and stepping from the last parameter back to the first.
float largestJump(const std::vector<float>& params, bool periodic, int steps) {
    float worst = 0.f;
    std::vector<float> prev = sampleWeights(params, 0.f, periodic);
    for (int i = 1; i <= steps; ++i) {
        const float t = i == steps ? 0.f : float(i) / float(steps); // the last step wraps
        const std::vector<float> w = sampleWeights(params, t, periodic);
        for (std::size_t s = 0; s < w.size(); ++s)
            worst = std::max(worst, std::fabs(w[s] - prev[s]));
        prev = w;
    }
    return worst;
}

const std::vector<float> kEight = {0.f, 0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f, 0.875f};

TEST(PemBlendPeriodic, WeightsAreContinuousAroundTheWholeLoop) {
    const int steps = 1000;
    // Linear weights between samples 1/8 apart change by 8/1000 per step at most.
    const float bound = 8.f / float(steps) * 1.001f;
    EXPECT_LE(largestJump(kEight, true, steps), bound);
    // The same loop on an open path jumps from the last sample to the first at the wrap:
    // what the periodic blend is for.
    EXPECT_GT(largestJump(kEight, false, steps), 0.9f);
}

TEST(PemBlendPeriodic, ExactAtSamplesAndHalfWayAcrossTheWrap) {
    for (std::size_t k = 0; k < kEight.size(); ++k) {
        const std::vector<float> w = sampleWeights(kEight, kEight[k], true);
        EXPECT_FLOAT_EQ(w[k], 1.f) << "sample " << k;
    }
    EXPECT_EQ(pemBlend(kEight, 0.9375f, false, true), (PemBlendWeights{7, 0, 0.5f}));
    EXPECT_EQ(pemBlend(kEight, 0.99f, true, true), (PemBlendWeights{0, 0, 0.f}));
    EXPECT_EQ(pemBlend(kEight, 0.9f, true, true), (PemBlendWeights{7, 7, 0.f}));
    // Parameters outside [0, 1) are the same point of the loop.
    EXPECT_EQ(pemBlend(kEight, 1.0625f, false, true), pemBlend(kEight, 0.0625f, false, true));
    EXPECT_EQ(pemBlend(kEight, -0.0625f, false, true), (PemBlendWeights{7, 0, 0.5f}));
    // Samples that do not start at 0: the wrap runs from the last to the first + 1.
    const std::vector<float> offset = {0.25f, 0.75f};
    EXPECT_EQ(pemBlend(offset, 0.f, false, true), (PemBlendWeights{1, 0, 0.5f}));
    EXPECT_EQ(pemBlend({0.5f}, 0.9f, false, true), (PemBlendWeights{0, 0, 0.f}));
}

} // namespace
} // namespace specula
