// The library face's device factory: devices by backend name, and a Renderer over them. "auto"
// takes CUDA if a CUDA device exists, else Vulkan on a hardware GPU, else the CPU (lavapipe,
// software Vulkan, is slower than the CPU device: only when asked for). Free of the command line:
// programs, bindings and tests use it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/frame/renderer.h"

namespace photon {

// One device of a backend: "auto", "cpu", "cuda" or "vulkan". Throws InputError for an unknown
// name and RuntimeError for a backend that is not available (not compiled in, or no device).
std::unique_ptr<Device> createDevice(const std::string& kind, const DeviceOptions& options = {});

// A renderer over one device per entry of a comma-separated list of backends ("cuda", "cpu,cpu",
// "cuda,cuda"): a frame's photon paths are split over them (and over the processes, under MPI:
// createCollective()). options.device is one device choice for all, or a comma-separated list
// with one entry each ("0,1").
std::unique_ptr<Renderer> createRenderer(const std::string& kinds, const DeviceOptions& options = {});

// How the renderers of several processes render together: over MPI where an MPI launcher
// started this process among others (and MPI is built: else RuntimeError), else alone.
std::unique_ptr<Collective> createCollective();

// The backends compiled into this build.
std::vector<std::string> compiledBackends();

// The most devices one renderer takes.
inline constexpr std::size_t kMaxDevices = 16;

}  // namespace photon
