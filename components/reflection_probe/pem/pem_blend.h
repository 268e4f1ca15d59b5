#pragma once
// Which two sample maps a PEM probe blends at a parameter, and with what weight (Hakura et
// al. 2001, §5: the samples nearest the current parameter are blended). One pure function,
// used by the store (it uploads a, b, wb) and by the CPU twin alike.
#include <cmath>
#include <cstddef>
#include <vector>

namespace specula {

struct PemBlendWeights {
    int a = 0;      // sample whose map gets weight 1 - wb
    int b = 0;      // sample whose map gets weight wb
    float wb = 0.f; // in [0, 1]

    bool operator==(const PemBlendWeights&) const = default;
};

// sampleParams strictly increasing in [0, 1), not empty. Between two samples the weight moves
// linearly from the lower to the upper one, so the blend is continuous in `parameter` and
// exact at every sample. Outside the samples' span: the end sample alone, or, on a periodic
// path (a closed loop such as the orbit, where parameter 1 is parameter 0 again), the blend
// of the last and the first sample across the wrap, so the loop has no seam. nearest: the
// nearer of the two bracketing samples alone (ties go to the upper one). A NaN parameter
// reads as the first sample.
inline PemBlendWeights pemBlend(const std::vector<float>& sampleParams, float parameter,
                                bool nearest, bool periodic = false) {
    const int n = int(sampleParams.size());
    if (n == 0 || parameter != parameter) return {0, 0, 0.f};
    if (periodic) parameter -= std::floor(parameter); // into [0, 1)
    const float first = sampleParams.front(), last = sampleParams.back();
    int a = 0, b = 0;
    float lo = 0.f, hi = 0.f;
    if (n > 1 && parameter > first && parameter < last) {
        b = 1;
        while (sampleParams[std::size_t(b)] < parameter)
            ++b;
        a = b - 1;
        lo = sampleParams[std::size_t(a)], hi = sampleParams[std::size_t(b)];
    } else if (!periodic || n == 1 || parameter == first || parameter == last) {
        return parameter <= first ? PemBlendWeights{0, 0, 0.f} : PemBlendWeights{n - 1, n - 1, 0.f};
    } else {
        // Across the wrap: from the last sample to the first one again at first + 1.
        if (parameter < first) parameter += 1.f;
        a = n - 1, b = 0;
        lo = last, hi = first + 1.f;
    }
    float wb = (parameter - lo) / (hi - lo);
    wb = wb < 0.f ? 0.f : (wb > 1.f ? 1.f : wb);
    if (nearest) return wb >= 0.5f ? PemBlendWeights{b, b, 0.f} : PemBlendWeights{a, a, 0.f};
    return {a, b, wb};
}

} // namespace specula
