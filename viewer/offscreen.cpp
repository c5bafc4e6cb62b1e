#include "offscreen.h"

#include "core/system/error.h"
#include "vulkan/check.h"
#include "vulkan/memory.h"

namespace photon::viewer {

OffscreenTarget::OffscreenTarget(const vk::Context& context, VkExtent2D extent, VkRenderPass renderPass)
    : context_(context), extent_(extent) {
    VkDevice device = context.device;
    VkImageCreateInfo imageInfo{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    imageInfo.imageType = VK_IMAGE_TYPE_2D;
    imageInfo.format = kOffscreenFormat;
    imageInfo.extent = {extent.width, extent.height, 1};
    imageInfo.mipLevels = 1;
    imageInfo.arrayLayers = 1;
    imageInfo.samples = VK_SAMPLE_COUNT_1_BIT;
    imageInfo.tiling = VK_IMAGE_TILING_OPTIMAL;
    imageInfo.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    imageInfo.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    imageInfo.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VK_CHECK(vkCreateImage(device, &imageInfo, nullptr, &image_));

    VkMemoryRequirements requirements;
    vkGetImageMemoryRequirements(device, image_, &requirements);
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.allocationSize = requirements.size;
    allocation.memoryTypeIndex = vk::findMemoryType(context, requirements.memoryTypeBits, vk::MemoryUse::Device);
    VK_CHECK(vkAllocateMemory(device, &allocation, nullptr, &memory_));
    VK_CHECK(vkBindImageMemory(device, image_, memory_, 0));

    view_ = createColorView(device, image_, kOffscreenFormat);
    framebuffer_ = createFramebuffer(device, renderPass, view_, extent);
}

OffscreenTarget::~OffscreenTarget() {
    VkDevice device = context_.device;
    vkDeviceWaitIdle(device);
    vkDestroyFramebuffer(device, framebuffer_, nullptr);
    vkDestroyImageView(device, view_, nullptr);
    vkDestroyImage(device, image_, nullptr);
    vkFreeMemory(device, memory_, nullptr);
}

}  // namespace photon::viewer
