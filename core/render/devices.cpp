#include "core/render/devices.h"

#include "core/system/error.h"
#include "cpu/cpu_device.h"
#ifdef PHOTON_HAVE_CUDA
#include "cuda/cuda_device.h"
#endif
#ifdef PHOTON_HAVE_VULKAN
#include "vulkan/vulkan_device.h"
#endif
#ifdef PHOTON_HAVE_MPI
#include "core/render/mpi_collective.h"
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

std::unique_ptr<Device> cpuDevice(const DeviceOptions& options) {
    if (!options.device.empty()) {
        throw InputError("--device " + options.device + ": the CPU backend has no devices to choose from");
    }
    return createCpuDevice();
}

}  // namespace

std::unique_ptr<Device> createDevice(const std::string& kind, [[maybe_unused]] const DeviceOptions& options) {
    if (kind == "cpu") {
        return cpuDevice(options);
    }
    if (kind == "cuda") {
#ifdef PHOTON_HAVE_CUDA
        return createCudaDevice(options);
#else
        throw RuntimeError("the CUDA backend is not compiled into this build");
#endif
    }
    if (kind == "vulkan") {
#ifdef PHOTON_HAVE_VULKAN
        return createVulkanDevice(options);
#else
        throw RuntimeError("the Vulkan backend is not compiled into this build");
#endif
    }
    if (kind == "auto") {
#ifdef PHOTON_HAVE_CUDA
        if (cudaDeviceCount() > 0) {
            return createCudaDevice(options);
        }
#endif
#ifdef PHOTON_HAVE_VULKAN
        // A real GPU; lavapipe (software) only when asked for: the CPU backend is faster.
        if (vulkanHardwareDeviceCount() > 0) {
            return createVulkanDevice(options);
        }
#endif
        return cpuDevice(options);
    }
    throw InputError("unknown backend '" + kind + "' (expected auto|cpu|cuda|vulkan)");
}

namespace {

std::vector<std::string> splitList(const std::string& list) {
    std::vector<std::string> items;
    std::size_t start = 0;
    for (;;) {
        std::size_t comma = list.find(',', start);
        items.push_back(list.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) {
            return items;
        }
        start = comma + 1;
    }
}

}  // namespace

std::unique_ptr<Renderer> createRenderer(const std::string& kinds, const DeviceOptions& options) {
    std::vector<std::string> names = splitList(kinds);
    std::vector<std::string> choices = splitList(options.device);
    for (const std::string& name : names) {
        if (name.empty()) {
            throw InputError("--backend '" + kinds + "': an empty entry in the list");
        }
    }
    if (names.size() > kMaxDevices) {
        throw InputError("--backend '" + kinds + "': " + std::to_string(names.size()) + " devices, at most " +
                         std::to_string(kMaxDevices));
    }
    if (choices.size() != 1 && choices.size() != names.size()) {
        throw InputError("--device '" + options.device + "': " + std::to_string(choices.size()) + " entries for " +
                         std::to_string(names.size()) + (names.size() == 1 ? " device" : " devices") + " (give one for all or one each)");
    }
    std::vector<std::unique_ptr<Device>> devices;
    for (std::size_t i = 0; i < names.size(); ++i) {
        DeviceOptions one = options;
        one.device = choices.size() == 1 ? choices.front() : choices[i];
        devices.push_back(createDevice(names[i], one));
    }
    return std::make_unique<Renderer>(std::move(devices), createCollective());
}

std::unique_ptr<Collective> createCollective() {
    if (!launchedByMpi()) {
        return createHostCollective();
    }
#ifdef PHOTON_HAVE_MPI
    return createMpiCollective();
#else
    throw RuntimeError("started by an MPI launcher with other processes, but this build has no MPI (libopenmpi-dev)");
#endif
}

}  // namespace photon
