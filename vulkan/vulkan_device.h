// The Vulkan compute device, for programs that only need the Device interface. The class itself,
// with what a windowed viewer needs, is in vulkan/device.h.
#pragma once

#include <memory>

#include "core/frame/device.h"

namespace photon {

// Creates the instance and device (options.device picks one by index or by part of its name;
// options.validation, or PHOTON_VULKAN_VALIDATION=1, turns on the validation layer, and any
// message it prints makes the frame throw RuntimeError). Throws RuntimeError if no device fits.
std::unique_ptr<Device> createVulkanDevice(const DeviceOptions& options);

// Vulkan devices that can run the backend; 0 when there is no loader, driver or device. Never throws.
int vulkanDeviceCount();

// The same, counting only hardware GPUs (not CPU implementations such as lavapipe).
int vulkanHardwareDeviceCount();

}  // namespace photon
