#pragma once
// Rows of an image in parallel, with the standard library's threads only: the runtime's CPU
// work (a glossy chain prefiltered at load) must not hand a threading library (TBB) to a host.
// The range is cut into small chunks taken in turn by one worker per hardware thread, so
// uneven rows still balance; the first exception a chunk throws is rethrown here.
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace specula {

// Calls chunk(lo, hi) for disjoint [lo, hi) covering [begin, end), from several threads.
template <typename Chunk> void parallelForRanges(int begin, int end, const Chunk& chunk) {
    const int count = end - begin;
    if (count <= 0) return;
    const int workers = std::clamp(int(std::thread::hardware_concurrency()), 1, count);
    const int grain = std::max(1, count / (8 * workers));
    std::atomic<int> next{begin};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto work = [&] {
        for (int lo = next.fetch_add(grain); lo < end; lo = next.fetch_add(grain)) {
            try {
                chunk(lo, std::min(end, lo + grain));
            } catch (...) {
                const std::lock_guard lock(failureMutex);
                if (!failure) failure = std::current_exception();
                next = end; // the others stop at their next chunk
            }
        }
    };
    std::vector<std::jthread> threads;
    for (int i = 1; i < workers; ++i)
        threads.emplace_back(work);
    work();
    threads.clear(); // joins
    if (failure) std::rethrow_exception(failure);
}

} // namespace specula
