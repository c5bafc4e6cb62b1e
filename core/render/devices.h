// The library face's device factory: a backend by name. "auto" takes CUDA if a CUDA device exists,
// else Vulkan on a hardware GPU, else the CPU (lavapipe, software Vulkan, is slower than the CPU
// backend: only when asked for). Free of the command line: programs, bindings and tests use it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/frame/backend.h"

namespace photon {

// Throws InputError for an unknown name and RuntimeError for a backend that is not available
// (not compiled in, or no device).
std::unique_ptr<Backend> createBackend(const std::string& kind, const BackendOptions& options = {});

// The backends compiled into this build.
std::vector<std::string> compiledBackends();

}  // namespace photon
