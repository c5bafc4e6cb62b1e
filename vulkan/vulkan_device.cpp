// createVulkanDevice() and vulkanDeviceCount(): the entry points core/render/devices.cpp uses.
#include "vulkan_device.h"

#include "device.h"
#include "context.h"

namespace photon {

std::unique_ptr<Device> createVulkanDevice(const DeviceOptions& options) {
    vk::ContextOptions contextOptions;
    contextOptions.device = options.device;
    contextOptions.validation = options.validation;
    return std::make_unique<vk::VulkanDevice>(std::make_shared<vk::Context>(contextOptions));
}

namespace {

int countDevices(bool hardwareOnly) {
    try {
        VkInstance instance = vk::createBareInstance();
        int count = 0;
        try {
            for (const vk::DeviceCandidate& c : vk::listDevices(instance, VK_NULL_HANDLE, {})) {
                bool software = c.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
                count += c.unsuitable.empty() && !(hardwareOnly && software) ? 1 : 0;
            }
        } catch (...) {
            count = 0;
        }
        vkDestroyInstance(instance, nullptr);
        return count;
    } catch (...) {
        return 0;
    }
}

}  // namespace

int vulkanDeviceCount() { return countDevices(false); }

int vulkanHardwareDeviceCount() { return countDevices(true); }

}  // namespace photon
