#pragma once
// Which two sample maps a PEM probe blends at a parameter, and with what weight (Hakura et
// al. 2001, §6: the samples nearest the current parameter are blended). One pure function,
// used by the store (it uploads a, b, wb) and by the CPU twin alike.
#include <cstddef>
#include <vector>

namespace specula {

struct PemBlendWeights {
    int a = 0;      // sample whose map gets weight 1 - wb
    int b = 0;      // sample whose map gets weight wb
    float wb = 0.f; // in [0, 1]

    bool operator==(const PemBlendWeights&) const = default;
};

// sampleParams strictly increasing, not empty. Below the first sample or above the last the
// end sample is used alone; between two samples the weight moves linearly from the lower to
// the upper one, so the blend is continuous in `parameter` and exact at every sample.
// nearest: the nearer of the two bracketing samples alone (ties go to the upper one). A NaN
// parameter reads as the first sample.
inline PemBlendWeights pemBlend(const std::vector<float>& sampleParams, float parameter,
                                bool nearest) {
    const int n = int(sampleParams.size());
    if (n == 0 || !(parameter > sampleParams.front())) return {0, 0, 0.f};
    if (parameter >= sampleParams.back()) return {n - 1, n - 1, 0.f};
    int b = 1;
    while (sampleParams[std::size_t(b)] < parameter)
        ++b;
    const int a = b - 1;
    const float lo = sampleParams[std::size_t(a)], hi = sampleParams[std::size_t(b)];
    float wb = (parameter - lo) / (hi - lo);
    wb = wb < 0.f ? 0.f : (wb > 1.f ? 1.f : wb);
    if (nearest) return wb >= 0.5f ? PemBlendWeights{b, b, 0.f} : PemBlendWeights{a, a, 0.f};
    return {a, b, wb};
}

} // namespace specula
