// What the display pass and the photon dots each own for their one pipeline: the layout of their
// own descriptor set (storage buffers only), the pipeline layout over it and their push
// constants, a pool holding one set of that layout, and the pipeline. Destroyed together, once the
// device is idle.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "vulkan/non_copyable.h"

namespace photon::viewer {

struct PassPipeline : vk::NonCopyable {
    explicit PassPipeline(VkDevice owner) : device(owner) {}
    ~PassPipeline();

    // The set layout of `count` storage-buffer bindings, and the one set of it.
    void createSet(const VkDescriptorSetLayoutBinding* bindings, std::uint32_t count);

    VkDevice device;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // the pass's own buffers
    VkPipelineLayout layout = VK_NULL_HANDLE;          // the pass's sets and its push constants
    VkDescriptorPool pool = VK_NULL_HANDLE;            // holds `set` alone
    VkDescriptorSet set = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

}  // namespace photon::viewer
