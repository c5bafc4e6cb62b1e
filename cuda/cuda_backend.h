// The CUDA backend: every stage on the GPU, one kernel per stage from shared/, every buffer of
// shared/bindings.h kept on the device across frames, images copied back through pinned memory.
#pragma once

#include <memory>

#include "core/frame/backend.h"
#include "stages.h"

namespace photon {

// BackendOptions.device: the CUDA device index (default 0). options.parity selects kernels built
// without FMA contraction, whose integer stages and hit points match the CPU backend exactly.
std::unique_ptr<Backend> createCudaBackend(const BackendOptions& options);

// Devices the CUDA runtime sees; 0 when there is no driver or no GPU. Never throws.
int cudaDeviceCount();

// Launch shapes of a CUDA backend (photon-bench sweeps them, starting from the backend's own,
// whose gridBlocks follow the device's SMs). No effect on other backends; they report the defaults.
LaunchConfig cudaLaunchConfig(Backend& backend);
void setCudaLaunchConfig(Backend& backend, const LaunchConfig& config);

// photon-bench's probe of the traversal: one ray through every pixel centre of the last frame's
// camera and image, nearest hit only, timed with CUDA events after a warm-up; the median of
// `repeats` launches. Zero times on other backends.
struct PrimaryRayTiming {
    double medianMs = 0.0;
    std::uint64_t rays = 0;
    std::uint64_t hits = 0;  // of one launch
};
PrimaryRayTiming timeCudaPrimaryRays(Backend& backend, int repeats);

}  // namespace photon
