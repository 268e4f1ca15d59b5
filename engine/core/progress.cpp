#include "progress.h"

#include <algorithm>
#include <cstdio>
#include <unistd.h>

namespace specula {

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)), tty_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
    if (tty_ && lastPercent_ >= 0) std::fputc('\n', stderr);
}

void ProgressBar::update(double fraction) {
    if (!tty_) return;
    const int percent = int(std::clamp(fraction, 0.0, 1.0) * 100.0);
    std::lock_guard lock(mutex_);
    if (percent == lastPercent_) return;
    lastPercent_ = percent;
    constexpr int kWidth = 30;
    const int filled = percent * kWidth / 100;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %5.1fs", label_.c_str(), filled,
                 "##############################", kWidth - filled, "", percent, seconds);
    std::fflush(stderr);
}

} // namespace specula
