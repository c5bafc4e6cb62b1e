// What the Vulkan device allows the buffers of shared/bindings.h (the plan itself is core's,
// core/frame/buffers.h), and how each buffer is used.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "context.h"
#include "core/frame/buffers.h"

namespace photon::vk {

// All buffers together within the largest device-local heap, each within maxStorageBufferRange.
MemoryLimits deviceMemoryLimits(const Context& context);

// Usage flags of the buffer behind each binding.
VkBufferUsageFlags bufferUsage(std::uint32_t binding);

}  // namespace photon::vk
