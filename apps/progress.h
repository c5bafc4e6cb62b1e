// A one-line progress bar on stderr, drawn only when stderr is a terminal (and not asked to be
// quiet), never wider than the terminal, so that each update overwrites the last.
#pragma once

#include <chrono>
#include <cstdint>

namespace photon {

class ProgressBar {
public:
    // Progress in frames (totalFrames > 1) or in time (totalSeconds > 0).
    ProgressBar(std::uint32_t totalFrames, double totalSeconds, bool enabled);
    void update(std::uint32_t frames, double seconds);
    void finish();

private:
    std::uint32_t totalFrames_;
    double totalSeconds_;
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace photon
