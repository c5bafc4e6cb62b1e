// Small Vulkan objects made the same way in several places (the backend, the viewer's passes).
// Each call is checked (VK_CHECK) and throws RuntimeError on failure.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

namespace photon::vk {

// A command pool whose buffers can be reset one by one, and one primary buffer from it.
struct CommandBuffer {
    VkCommandPool pool = VK_NULL_HANDLE;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
};
CommandBuffer createCommandBuffer(VkDevice device, std::uint32_t queueFamily);

VkFence createFence(VkDevice device);

// A pipeline layout of `setCount` descriptor set layouts and one push-constant range.
VkPipelineLayout createPipelineLayout(VkDevice device, const VkDescriptorSetLayout* sets, std::uint32_t setCount,
                                      VkPushConstantRange push);

// A pool for exactly one descriptor set of `storageBuffers` storage buffers, and that set.
struct SingleDescriptorSet {
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
};
SingleDescriptorSet allocateSingleSet(VkDevice device, VkDescriptorSetLayout layout, std::uint32_t storageBuffers);

// Points binding `binding` of `set` at the first `size` bytes of `buffer`. Only between frames.
void writeBufferDescriptor(VkDevice device, VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                           VkBuffer buffer, VkDeviceSize size);

}  // namespace photon::vk
