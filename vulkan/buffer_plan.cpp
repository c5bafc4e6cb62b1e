#include "buffer_plan.h"

#include <algorithm>

namespace photon::vk {

MemoryLimits deviceMemoryLimits(const Context& context) {
    MemoryLimits limits;
    limits.device = context.properties.deviceName;
    limits.memory = "device-local memory";
    const VkPhysicalDeviceMemoryProperties& memory = context.memoryProperties;
    for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h) {
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
            limits.total = std::max<std::uint64_t>(limits.total, memory.memoryHeaps[h].size);
        }
    }
    limits.perBuffer = context.properties.limits.maxStorageBufferRange;
    limits.perBufferLimit = "maxStorageBufferRange";
    return limits;
}

VkBufferUsageFlags bufferUsage(std::uint32_t binding) {
    VkBufferUsageFlags copies = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (binding == BINDING_PARAMS) {
        return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | copies;
    }
    if (binding == BINDING_COUNTERS) {
        return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | copies;
    }
    return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | copies;
}

}  // namespace photon::vk
