#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace photon {

ProgressBar::ProgressBar(std::uint32_t total)
    : total_(total), enabled_(total > 1 && isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

void ProgressBar::update(std::uint32_t done) {
    if (!enabled_) {
        return;
    }
    auto now = std::chrono::steady_clock::now();
    if (done < total_ && now - lastDraw_ < std::chrono::milliseconds(100)) {
        return;
    }
    lastDraw_ = now;
    constexpr int kWidth = 30;
    int filled = int(std::uint64_t(done) * kWidth / total_);
    double seconds = std::chrono::duration<double>(now - start_).count();
    double fps = seconds > 0.0 ? done / seconds : 0.0;
    std::fprintf(stderr, "\r[%.*s%*s] %u/%u frames, %.1f frames/s ", filled, "##############################",
                 kWidth - filled, "", done, total_, fps);
    std::fflush(stderr);
}

void ProgressBar::finish() {
    if (enabled_) {
        std::fprintf(stderr, "\n");
    }
}

}  // namespace photon
