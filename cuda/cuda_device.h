// The CUDA device: every stage on the GPU, one kernel per stage from shared/, every buffer of
// shared/bindings.h kept on the device across frames, images copied back through pinned memory.
#pragma once

#include <memory>

#include "core/frame/device.h"
#include "stages.h"

namespace photon {

// DeviceOptions.device: the CUDA device index (default 0). options.parity selects kernels built
// without FMA contraction, whose integer stages and hit points match the CPU backend exactly.
std::unique_ptr<Device> createCudaDevice(const DeviceOptions& options);

// Devices the CUDA runtime sees; 0 when there is no driver or no GPU. Never throws.
int cudaDeviceCount();

// Launch shapes of a CUDA device (photon-bench sweeps them, starting from the backend's own,
// whose gridBlocks follow its SMs). No effect on other devices; they report the defaults.
LaunchConfig cudaLaunchConfig(Device& device);
void setCudaLaunchConfig(Device& device, const LaunchConfig& config);

// photon-bench's probe of the traversal: one ray through every pixel centre of the last frame's
// camera and image, nearest hit only, timed with CUDA events after a warm-up; the median of
// `repeats` launches. Zero times on other devices.
struct PrimaryRayTiming {
    double medianMs = 0.0;
    std::uint64_t rays = 0;
    std::uint64_t hits = 0;  // of one launch
};
PrimaryRayTiming timeCudaPrimaryRays(Device& device, int repeats);

}  // namespace photon
