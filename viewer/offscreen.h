// The image the viewer draws into without a window (--offscreen): the same frame, the same
// display pass and HUD, for machines that have a GPU but no display.
#pragma once

#include <vulkan/vulkan.h>

#include "target.h"
#include "vulkan/context.h"
#include "vulkan/non_copyable.h"

namespace photon::viewer {

class OffscreenTarget : vk::NonCopyable {
public:
    // A kOffscreenFormat image of `extent` with a framebuffer for `renderPass`.
    OffscreenTarget(const vk::Context& context, VkExtent2D extent, VkRenderPass renderPass);
    ~OffscreenTarget();

    TargetImage target() const { return {image_, framebuffer_, extent_, 0}; }

private:
    const vk::Context& context_;
    VkExtent2D extent_{};
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
};

}  // namespace photon::viewer
