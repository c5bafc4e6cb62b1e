// What every buffer of a frame needs for a photon budget and an image size, checked against the
// device before anything is allocated: a request that cannot fit is refused with InputError
// naming the buffer, its size, the limit and what to lower.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "context.h"
#include "core/frame_setup.h"
#include "scan.h"
#include "shared/bindings.h"

namespace photon::vk {

struct BufferPlan {
    VkDeviceSize bytes[BINDING_COUNT] = {};  // by binding; uploadScene fills the scene's
    ScanPlan scan;                           // the levels of the cell-count scan, in cellStart
};

BufferPlan planBuffers(const PhotonBudget& budget, std::uint32_t width, std::uint32_t height, std::uint32_t scanGroupSize);

// Throws InputError if a binding exceeds the device's maxStorageBufferRange (or
// maxUniformBufferRange), or all buffers together exceed its device-local memory.
void checkLimits(const Context& context, const BufferPlan& plan, std::uint32_t width, std::uint32_t height);

// Usage flags of the buffer behind each binding.
VkBufferUsageFlags bufferUsage(std::uint32_t binding);

// The binding's name in shared/bindings.h, for messages.
const char* bindingName(std::uint32_t binding);

}  // namespace photon::vk
