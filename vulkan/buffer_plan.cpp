// Buffer sizes for a budget and image, and the device limits they must respect.
#include "buffer_plan.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "glsl/dispatch.h"

namespace photon::vk {
namespace {

std::string mib(VkDeviceSize bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
    return text;
}

bool isSceneBinding(std::uint32_t b) { return b >= BINDING_SPHERES && b <= BINDING_TARGETS; }

const char* whatToLower(std::uint32_t binding) {
    switch (binding) {
        case BINDING_PHOTONS:
        case BINDING_PHOTON_KEYS:
        case BINDING_SORTED_PHOTONS: return "lower the photon count (photons) or the photon capacity per path";
        case BINDING_CELL_COUNTS:
        case BINDING_CELL_START: return "lower the photon count (photons) or, for the bounded grid, its resolution";
        case BINDING_HIT_POINTS:
        case BINDING_FRAME:
        case BINDING_ACCUMULATION: return "lower the resolution";
        default: return "simplify the scene";
    }
}

}  // namespace

BufferPlan planBuffers(const PhotonBudget& budget, std::uint32_t width, std::uint32_t height, std::uint32_t scanGroupSize) {
    BufferPlan plan;
    plan.scan = planScan(budget, scanGroupSize);
    VkDeviceSize photons = std::max<VkDeviceSize>(budget.totalCapacity(), 1);
    VkDeviceSize pixels = VkDeviceSize(width) * height;
    plan.bytes[BINDING_PARAMS] = sizeof(FrameParams);
    plan.bytes[BINDING_PHOTONS] = photons * sizeof(Photon);
    plan.bytes[BINDING_PHOTON_KEYS] = photons * sizeof(std::uint32_t);
    plan.bytes[BINDING_SORTED_PHOTONS] = photons * sizeof(Photon);
    plan.bytes[BINDING_CELL_COUNTS] = VkDeviceSize(budget.totalCellEntries()) * sizeof(std::uint32_t);
    plan.bytes[BINDING_CELL_START] = plan.scan.cellStartEntries * sizeof(std::uint32_t);
    plan.bytes[BINDING_COUNTERS] = COUNTER_WORDS * sizeof(std::uint32_t);
    plan.bytes[BINDING_HIT_POINTS] = pixels * sizeof(HitPoint);
    plan.bytes[BINDING_FRAME] = pixels * sizeof(glm::vec4);
    plan.bytes[BINDING_ACCUMULATION] = pixels * sizeof(glm::vec4);
    return plan;
}

void checkLimits(const Context& context, const BufferPlan& plan, std::uint32_t width, std::uint32_t height) {
    const VkPhysicalDeviceLimits& limits = context.properties.limits;
    std::string device = context.properties.deviceName;
    VkDeviceSize total = 0;
    for (std::uint32_t b = 0; b < BINDING_COUNT; ++b) {
        VkDeviceSize bytes = plan.bytes[b];
        total += bytes;
        bool uniform = b == BINDING_PARAMS;
        VkDeviceSize range = uniform ? limits.maxUniformBufferRange : limits.maxStorageBufferRange;
        if (bytes > range) {
            std::string size = isSceneBinding(b) ? "" : " at " + std::to_string(width) + "×" + std::to_string(height);
            throw InputError(std::string("Vulkan: buffer '") + bindingName(b) + "' needs " + mib(bytes) + size +
                             ", more than the " + mib(range) + " one " + (uniform ? "uniform" : "storage") +
                             " buffer may span on " + device + (uniform ? " (maxUniformBufferRange)" : " (maxStorageBufferRange)") +
                             "; " + whatToLower(b));
        }
    }
    VkDeviceSize heap = 0;
    const VkPhysicalDeviceMemoryProperties& memory = context.memoryProperties;
    for (std::uint32_t h = 0; h < memory.memoryHeapCount; ++h) {
        if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
            heap = std::max(heap, memory.memoryHeaps[h].size);
        }
    }
    if (total > heap) {
        throw InputError("Vulkan: the buffers need " + mib(total) + " of device memory in all, more than the " +
                         mib(heap) + " of " + device + "; lower the photon count (photons) or the resolution");
    }
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

const char* bindingName(std::uint32_t binding) {
    static const char* const names[BINDING_COUNT] = {
        "params",      "spheres",    "planes",   "quads",         "triangles", "materials",
        "lights",      "targets",    "photons",  "photonKeys",    "sortedPhotons",
        "cellCounts",  "cellStart",  "counters", "hitPoints",     "frameRadiance", "accumulation"};
    return binding < BINDING_COUNT ? names[binding] : "?";
}

}  // namespace photon::vk
