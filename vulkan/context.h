// The Vulkan instance and device every part of the backend runs on: instance (with validation and
// a messenger when asked), device selection, one queue. A windowed viewer creates it with its
// surface and swapchain extensions and hands it to the backend, so both share one device.
#pragma once

#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "non_copyable.h"

namespace photon::vk {

struct ContextOptions {
    std::string device;                           // index, or a case-insensitive part of the name;
                                                  // empty: the first discrete GPU, else the first device
    bool validation = false;                      // Khronos validation with synchronization checks;
                                                  // also on when PHOTON_VULKAN_VALIDATION=1
    std::vector<const char*> instanceExtensions;  // e.g. VK_KHR_surface and the window system's
    std::vector<const char*> deviceExtensions;    // e.g. VK_KHR_swapchain
    bool graphics = false;                        // the queue must also draw (a viewer's render passes)
    // Called once the instance exists: a window's surface, which the queue must then present to.
    // The context destroys it.
    std::function<VkSurfaceKHR(VkInstance)> createSurface;
};

// What a device offers, for choosing one (and for vulkanDeviceCount()).
struct DeviceCandidate {
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    std::uint32_t queueFamily = 0;  // a family with compute (and graphics, present, when asked for)
    std::string unsuitable;         // why it cannot run Photon; empty if it can
};

// Every physical device of the instance, with whether and why it cannot run the backend.
std::vector<DeviceCandidate> listDevices(VkInstance instance, VkSurfaceKHR surface,
                                         const std::vector<const char*>& deviceExtensions, bool graphics = false);

// The candidate the options ask for; throws RuntimeError naming the devices if none fits.
const DeviceCandidate& pickDevice(const std::vector<DeviceCandidate>& candidates, const std::string& request);

// An instance with no layers, for counting devices; throws if there is no Vulkan loader or driver.
VkInstance createBareInstance();

class Context : NonCopyable {
public:
    explicit Context(const ContextOptions& options);
    ~Context();

    // Throws RuntimeError with every validation message since the last call (each was also
    // printed when it arrived). `where` says what was running.
    void checkValidation(const char* where);
    bool validationEnabled() const { return messenger != VK_NULL_HANDLE; }

    // Instance and device.
    VkInstance instance = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;  // validation messages, when enabled
    VkSurfaceKHR surface = VK_NULL_HANDLE;                // the caller's window, if any
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;

    // The one queue: compute (and graphics and present, when asked for).
    VkQueue queue = VK_NULL_HANDLE;
    std::uint32_t queueFamily = 0;
    std::uint32_t timestampValidBits = 0;  // 0: the queue cannot time stages

    // What the device offers.
    VkPhysicalDeviceProperties properties{};        // name, limits, timestampPeriod
    VkPhysicalDeviceMemoryProperties memoryProperties{};
    std::uint32_t subgroupSize = 0;                 // the default subgroup size (8 on lavapipe, 32 on NVIDIA)
    std::uint32_t maxSubgroupSize = 0;              // largest subgroup a compute pipeline may get
    // PHOTON_VULKAN_PIPELINE_STATISTICS=1 on a device with VK_KHR_pipeline_executable_properties:
    // each pipeline's compiler statistics (registers, spills, ...) go to stderr as it is built, to
    // compare the driver's compilation of a stage with nvcc's (ptxas -v).
    bool pipelineStatistics = false;

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT type,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);
    void createInstance(const ContextOptions& options, bool validation);
    void createDevice(const ContextOptions& options);
    void destroy();

    std::mutex messagesMutex_;
    std::vector<std::string> messages_;  // validation warnings and errors not yet reported
};

}  // namespace photon::vk
