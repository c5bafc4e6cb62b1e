#include "objects.h"

#include "check.h"

namespace photon::vk {

CommandBuffer createCommandBuffer(VkDevice device, std::uint32_t queueFamily) {
    CommandBuffer out;
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queueFamily;
    VK_CHECK(vkCreateCommandPool(device, &poolInfo, nullptr, &out.pool));
    VkCommandBufferAllocateInfo allocation{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocation.commandPool = out.pool;
    allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocation.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(device, &allocation, &out.cmd));
    return out;
}

VkFence createFence(VkDevice device) {
    VkFence fence = VK_NULL_HANDLE;
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(device, &fenceInfo, nullptr, &fence));
    return fence;
}

VkPipelineLayout createPipelineLayout(VkDevice device, const VkDescriptorSetLayout* sets, std::uint32_t setCount,
                                      VkPushConstantRange push) {
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = setCount;
    layoutInfo.pSetLayouts = sets;
    layoutInfo.pushConstantRangeCount = 1;
    layoutInfo.pPushConstantRanges = &push;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout));
    return layout;
}

SingleDescriptorSet allocateSingleSet(VkDevice device, VkDescriptorSetLayout layout, std::uint32_t storageBuffers) {
    SingleDescriptorSet out;
    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, storageBuffers};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    VK_CHECK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &out.pool));
    VkDescriptorSetAllocateInfo allocation{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocation.descriptorPool = out.pool;
    allocation.descriptorSetCount = 1;
    allocation.pSetLayouts = &layout;
    VK_CHECK(vkAllocateDescriptorSets(device, &allocation, &out.set));
    return out;
}

void writeBufferDescriptor(VkDevice device, VkDescriptorSet set, std::uint32_t binding, VkDescriptorType type,
                           VkBuffer buffer, VkDeviceSize size) {
    VkDescriptorBufferInfo info{buffer, 0, size};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.dstBinding = binding;
    write.descriptorCount = 1;
    write.descriptorType = type;
    write.pBufferInfo = &info;
    vkUpdateDescriptorSets(device, 1, &write, 0, nullptr);
}

}  // namespace photon::vk
