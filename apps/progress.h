// A one-line progress bar on stderr, drawn only when stderr is a terminal.
#pragma once

#include <chrono>
#include <cstdint>

namespace photon {

class ProgressBar {
public:
    explicit ProgressBar(std::uint32_t total);
    void update(std::uint32_t done);
    void finish();

private:
    std::uint32_t total_;
    bool enabled_;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace photon
