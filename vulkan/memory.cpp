// Buffer allocation (one VkDeviceMemory per buffer: the backend has about twenty) and one-off
// transfers through staging buffers.
#include "memory.h"

#include <cstring>
#include <string>
#include <utility>

#include "check.h"
#include "core/system/error.h"

namespace photon::vk {

std::uint32_t findMemoryType(const Context& context, std::uint32_t allowedTypes, MemoryUse use) {
    VkMemoryPropertyFlags required = use == MemoryUse::Device
                                         ? VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT
                                         : VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    VkMemoryPropertyFlags preferred = use == MemoryUse::Readback ? VK_MEMORY_PROPERTY_HOST_CACHED_BIT : 0;
    const VkPhysicalDeviceMemoryProperties& memory = context.memoryProperties;
    for (VkMemoryPropertyFlags wanted : {required | preferred, required}) {
        for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
            if ((allowedTypes & (1u << i)) && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) {
                return i;
            }
        }
    }
    throw RuntimeError("no Vulkan memory type fits a buffer or image");
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStages, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStages, VkAccessFlags dstAccess) {
    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    vkCmdPipelineBarrier(cmd, srcStages, dstStages, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

Buffer::Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use)
    : device_(context.device), size_(size) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer_));
    try {
        VkMemoryRequirements requirements;
        vkGetBufferMemoryRequirements(device_, buffer_, &requirements);
        VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        allocation.allocationSize = requirements.size;
        allocation.memoryTypeIndex = findMemoryType(context, requirements.memoryTypeBits, use);
        VkResult result = vkAllocateMemory(device_, &allocation, nullptr, &memory_);
        if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY) {
            throw RuntimeError("out of Vulkan memory allocating " + std::to_string(size >> 20) +
                               " MiB; lower the photon count or the resolution");
        }
        VK_CHECK(result);
        VK_CHECK(vkBindBufferMemory(device_, buffer_, memory_, 0));
        if (use != MemoryUse::Device) {
            VK_CHECK(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
        }
    } catch (...) {
        release();
        throw;
    }
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
    if (this != &other) {
        release();
        device_ = std::exchange(other.device_, VK_NULL_HANDLE);
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

void Buffer::release() {
    if (buffer_ != VK_NULL_HANDLE) {
        vkDestroyBuffer(device_, buffer_, nullptr);
    }
    if (memory_ != VK_NULL_HANDLE) {
        vkFreeMemory(device_, memory_, nullptr);  // unmaps too
    }
    buffer_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
    mapped_ = nullptr;
    size_ = 0;
}

Transfers::Transfers(const Context& context) : context_(context) {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily;
    VK_CHECK(vkCreateCommandPool(context.device, &poolInfo, nullptr, &pool_));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(context.device, &fenceInfo, nullptr, &fence_));
}

Transfers::~Transfers() {
    vkDestroyFence(context_.device, fence_, nullptr);
    vkDestroyCommandPool(context_.device, pool_, nullptr);
}

void Transfers::run(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo allocation{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocation.commandPool = pool_;
    allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocation.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(context_.device, &allocation, &cmd));
    try {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
        record(cmd);
        VK_CHECK(vkEndCommandBuffer(cmd));
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        VK_CHECK(vkQueueSubmit(context_.queue, 1, &submit, fence_));
        VK_CHECK(vkWaitForFences(context_.device, 1, &fence_, VK_TRUE, UINT64_MAX));
        VK_CHECK(vkResetFences(context_.device, 1, &fence_));
    } catch (...) {
        vkFreeCommandBuffers(context_.device, pool_, 1, &cmd);
        throw;
    }
    vkFreeCommandBuffers(context_.device, pool_, 1, &cmd);
}

void Transfers::upload(const Buffer& target, const void* data, VkDeviceSize size, VkDeviceSize offset) {
    if (size == 0) {
        return;
    }
    Buffer staging(context_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload);
    std::memcpy(staging.mapped(), data, size);
    run([&](VkCommandBuffer cmd) {
        // Earlier commands are done with the target before the copy overwrites it.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT);
        VkBufferCopy region{0, offset, size};
        vkCmdCopyBuffer(cmd, staging.handle(), target.handle(), 1, &region);
        // The copy is written before any later command (of any later submission) uses the buffer.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
    });
}

void Transfers::download(const Buffer& source, VkDeviceSize offset, void* data, VkDeviceSize size) {
    if (size == 0) {
        return;
    }
    Buffer staging(context_, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
    run([&](VkCommandBuffer cmd) {
        // Every earlier command's writes are done and visible before the copy reads them.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                      VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy region{offset, 0, size};
        vkCmdCopyBuffer(cmd, source.handle(), staging.handle(), 1, &region);
        // The copy is written before the host reads the staging buffer.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
    });
    std::memcpy(data, staging.mapped(), size);
}

}  // namespace photon::vk
