// The image a frame is drawn into: a swapchain image (windowed) or the offscreen image.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

namespace photon::viewer {

struct TargetImage {
    VkImage image = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;  // for the display pass's render pass
    VkExtent2D extent{};
    std::uint32_t index = 0;                     // swapchain image index (0 offscreen)
};

// The colour format the viewer draws in: 8-bit UNORM, because the display shader encodes sRGB
// itself (as photon-render's PNG writer does) and Dear ImGui expects its colours stored as given.
constexpr VkFormat kOffscreenFormat = VK_FORMAT_B8G8R8A8_UNORM;

// A 2D view of the colour of `image` (one level, one layer), in `format`.
VkImageView createColorView(VkDevice device, VkImage image, VkFormat format);

// A framebuffer of `view` alone, of `extent`, for `renderPass` (the display pass's).
VkFramebuffer createFramebuffer(VkDevice device, VkRenderPass renderPass, VkImageView view, VkExtent2D extent);

}  // namespace photon::viewer
