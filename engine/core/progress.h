#pragma once
// A one-line progress bar on stderr, drawn only when stderr is a terminal (logs and CI stay
// clean). Thread-safe: update() may be called from worker threads.
#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace specula {

class ProgressBar {
public:
    explicit ProgressBar(std::string label);
    ~ProgressBar(); // finishes the line
    void update(double fraction);

private:
    std::string label_;
    bool tty_;
    std::mutex mutex_;
    int lastPercent_ = -1;
    std::chrono::steady_clock::time_point start_;
};

} // namespace specula
