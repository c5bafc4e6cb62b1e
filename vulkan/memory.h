// Buffers with their own memory, and copies between host and device through staging buffers.
// Working buffers live in device-local memory: on a discrete GPU, a frame buffer in host-visible
// memory was measured 6× slower.
#pragma once

#include <functional>
#include <utility>

#include <vulkan/vulkan.h>

#include "context.h"

namespace photon::vk {

enum class MemoryUse {
    Device,    // device-local, reached only through copies
    Upload,    // host-visible and coherent, written by the host
    Readback,  // host-visible and coherent, cached where possible, read by the host
};

// The memory type for a resource whose requirements allow `allowedTypes`, for `use`.
std::uint32_t findMemoryType(const Context& context, std::uint32_t allowedTypes, MemoryUse use);

// A VkBuffer and its VkDeviceMemory, freed together. Move-only.
class Buffer {
public:
    Buffer() = default;
    Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use);
    ~Buffer() { release(); }
    Buffer(Buffer&& other) noexcept { *this = std::move(other); }
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }  // host-visible buffers only

private:
    void release();

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

// A global memory barrier: the `srcAccess` accesses of `srcStages` in earlier commands happen
// before, and are visible to, the `dstAccess` accesses of `dstStages` in later ones. Every barrier
// of the backend is one of these, with a sentence where it is used saying what it orders.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags srcStages, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStages, VkAccessFlags dstAccess);

// Commands run once and waited for: uploads, readbacks, anything outside a frame.
class Transfers : NonCopyable {
public:
    explicit Transfers(const Context& context);
    ~Transfers();

    // Records commands with `record`, submits them and waits until they are done.
    void run(const std::function<void(VkCommandBuffer)>& record);

    // Host → device buffer (from byte `offset`), through a staging buffer. Later commands of any
    // submission see the data.
    void upload(const Buffer& target, const void* data, VkDeviceSize size, VkDeviceSize offset = 0);

    // Device buffer → host, through a staging buffer, after every earlier command's writes.
    void download(const Buffer& source, VkDeviceSize offset, void* data, VkDeviceSize size);

private:
    const Context& context_;
    VkCommandPool pool_ = VK_NULL_HANDLE;  // transient command buffers, one per run()
    VkFence fence_ = VK_NULL_HANDLE;       // signalled when a run() is done
};

}  // namespace photon::vk
