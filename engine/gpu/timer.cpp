#include "engine/gpu/timer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace specula::gpu {

GpuTimer::GpuTimer() : query_(Query::create(GL_TIME_ELAPSED)) {}

void GpuTimer::begin() {
    assert(!pending_ && "GpuTimer::begin() twice without end()");
    begun_ = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query_.id());
    pending_ = true;
}

void GpuTimer::end() {
    assert(pending_ && "GpuTimer::end() without begin()");
    glEndQuery(GL_TIME_ELAPSED);
    pending_ = false;
}

double GpuTimer::resultMs() {
    GLuint64 ns = 0;
    // GL_QUERY_RESULT blocks until the GPU has finished the measured commands.
    glGetQueryObjectui64v(query_.id(), GL_QUERY_RESULT, &ns);
    const double wallMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begun_)
            .count();
    const double ms = double(ns) * 1e-6;
    // Slack for a GPU clock that runs a little fast against the CPU's.
    if (ms > wallMs * 1.05 + 0.01) return std::numeric_limits<double>::quiet_NaN();
    return ms;
}

double GpuTimer::measure(const std::function<void()>& pass) {
    begin();
    pass();
    end();
    return resultMs();
}

double medianMs(std::vector<double> samples) {
    std::erase_if(samples, [](double s) { return !std::isfinite(s); });
    if (samples.empty()) return std::numeric_limits<double>::quiet_NaN();
    const std::size_t mid = samples.size() / 2;
    std::nth_element(samples.begin(), samples.begin() + std::ptrdiff_t(mid), samples.end());
    const double upper = samples[mid];
    if (samples.size() % 2 == 1) return upper;
    const double lower = *std::max_element(samples.begin(), samples.begin() + std::ptrdiff_t(mid));
    return 0.5 * (lower + upper);
}

Quartiles quartilesMs(std::vector<double> samples) {
    std::erase_if(samples, [](double s) { return !std::isfinite(s); });
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (samples.empty()) return {nan, nan, nan};
    std::sort(samples.begin(), samples.end());
    const auto at = [&](double q) {
        const double pos = q * double(samples.size() - 1);
        const std::size_t i = std::size_t(pos);
        const double next = samples[std::min(i + 1, samples.size() - 1)];
        return samples[i] + (pos - double(i)) * (next - samples[i]);
    };
    return {at(0.25), at(0.5), at(0.75)};
}

} // namespace specula::gpu
