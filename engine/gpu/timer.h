#pragma once
// GPU time of a pass with GL_TIME_ELAPSED queries. On a real GPU this is the time the
// commands took on the device; on llvmpipe it is CPU rasteriser time, meaningful only as a
// ratio to another pass measured the same way (see docs/design.md §6).
#include "engine/gpu/gl_objects.h"

#include <chrono>
#include <functional>
#include <vector>

namespace specula::gpu {

class GpuTimer {
public:
    GpuTimer(); // needs a current context
    // Time-elapsed queries do not nest: only one GpuTimer may be between begin() and end().
    void begin();
    void end();
    // Waits for the result of the last begin()/end() pair. Milliseconds, or NaN when the
    // driver's figure is impossible: longer than the wall-clock time from begin() until the
    // result arrived. (Mesa llvmpipe 22.x reports its clock's absolute time for the first
    // query of a context that covers draws; warm up with one throw-away measurement.)
    double resultMs();
    // begin(); pass(); end(); resultMs().
    double measure(const std::function<void()>& pass);

private:
    Query query_;
    bool pending_ = false;
    std::chrono::steady_clock::time_point begun_{};
};

// Median of the finite samples (the mean of the middle two for an even count); NaN samples
// (rejected timer results) are left out; NaN when none is left.
double medianMs(std::vector<double> samples);

// The quartiles of the finite samples (linear interpolation between order statistics, so
// the middle one is medianMs), for a row's spread: two rows whose interquartile ranges overlap
// cannot be told apart. NaN in all three when no finite sample is left.
struct Quartiles {
    double q1, median, q3;
    double iqr() const { return q3 - q1; }
};
Quartiles quartilesMs(std::vector<double> samples);

} // namespace specula::gpu
