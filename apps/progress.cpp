#include "progress.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace photon {
namespace {

int terminalColumns() {
    winsize size{};
    if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) {
        return size.ws_col;
    }
    return 80;
}

}  // namespace

ProgressBar::ProgressBar(std::uint32_t totalFrames, double totalSeconds, bool enabled)
    : totalFrames_(totalFrames),
      totalSeconds_(totalSeconds),
      enabled_(enabled && (totalFrames > 1 || totalSeconds > 0.0) && isatty(STDERR_FILENO)),
      lastDraw_(std::chrono::steady_clock::now()) {}

void ProgressBar::update(std::uint32_t frames, double seconds) {
    if (!enabled_) {
        return;
    }
    auto now = std::chrono::steady_clock::now();
    bool last = totalSeconds_ > 0.0 ? seconds >= totalSeconds_ : frames >= totalFrames_;
    if (!last && now - lastDraw_ < std::chrono::milliseconds(100)) {
        return;
    }
    lastDraw_ = now;
    double fraction = totalSeconds_ > 0.0 ? seconds / totalSeconds_ : double(frames) / double(totalFrames_);
    fraction = std::clamp(fraction, 0.0, 1.0);
    char text[128];
    double fps = seconds > 0.0 ? frames / seconds : 0.0;
    if (totalSeconds_ > 0.0) {
        std::snprintf(text, sizeof text, " %u frames, %.1f/%.1f s, %.1f frames/s", frames, seconds, totalSeconds_, fps);
    } else {
        std::snprintf(text, sizeof text, " %u/%u frames, %.1f frames/s", frames, totalFrames_, fps);
    }
    // The line is one column short of the terminal's width, so that it never wraps.
    int width = terminalColumns() - 1;
    std::string line(text);
    int bar = std::min(30, width - int(line.size()) - 2);
    if (bar >= 5) {
        int filled = int(fraction * bar + 0.5);
        line = "[" + std::string(filled, '#') + std::string(bar - filled, ' ') + "]" + line;
    }
    if (int(line.size()) > width) {
        line.resize(std::max(0, width));
    }
    std::fprintf(stderr, "\r%s\x1b[K", line.c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void ProgressBar::finish() {
    if (enabled_ && drawn_) {
        std::fprintf(stderr, "\n");
    }
}

}  // namespace photon
