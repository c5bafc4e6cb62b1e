#include "core/render/devices.h"

#include "core/system/error.h"
#include "cpu/cpu_backend.h"
#ifdef PHOTON_HAVE_CUDA
#include "cuda/cuda_backend.h"
#endif
#ifdef PHOTON_HAVE_VULKAN
#include "vulkan/vulkan_backend.h"
#endif

namespace photon {

std::vector<std::string> compiledBackends() {
    std::vector<std::string> names{"cpu"};
#ifdef PHOTON_HAVE_CUDA
    names.push_back("cuda");
#endif
#ifdef PHOTON_HAVE_VULKAN
    names.push_back("vulkan");
#endif
    return names;
}

namespace {

std::unique_ptr<Backend> cpuBackend(const BackendOptions& options) {
    if (!options.device.empty()) {
        throw InputError("--device " + options.device + ": the CPU backend has no devices to choose from");
    }
    return createCpuBackend();
}

}  // namespace

std::unique_ptr<Backend> createBackend(const std::string& kind, [[maybe_unused]] const BackendOptions& options) {
    if (kind == "cpu") {
        return cpuBackend(options);
    }
    if (kind == "cuda") {
#ifdef PHOTON_HAVE_CUDA
        return createCudaBackend(options);
#else
        throw RuntimeError("the CUDA backend is not compiled into this build");
#endif
    }
    if (kind == "vulkan") {
#ifdef PHOTON_HAVE_VULKAN
        return createVulkanBackend(options);
#else
        throw RuntimeError("the Vulkan backend is not compiled into this build");
#endif
    }
    if (kind == "auto") {
#ifdef PHOTON_HAVE_CUDA
        if (cudaDeviceCount() > 0) {
            return createCudaBackend(options);
        }
#endif
#ifdef PHOTON_HAVE_VULKAN
        // A real GPU; lavapipe (software) only when asked for: the CPU backend is faster.
        if (vulkanHardwareDeviceCount() > 0) {
            return createVulkanBackend(options);
        }
#endif
        return cpuBackend(options);
    }
    throw InputError("unknown backend '" + kind + "' (expected auto|cpu|cuda|vulkan)");
}

}  // namespace photon
