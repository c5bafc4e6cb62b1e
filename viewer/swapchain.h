// The window's swapchain: its images, their views and framebuffers, and one "rendering done"
// semaphore per image (a present may still wait on the previous one when the image comes back).
// Recreated on resize, on VK_ERROR_OUT_OF_DATE_KHR and when vsync is switched.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "target.h"
#include "vulkan/context.h"

namespace photon::viewer {

class Swapchain : vk::NonCopyable {
public:
    explicit Swapchain(const vk::Context& context);
    ~Swapchain();

    // A UNORM 8-bit format the surface offers (see target.h), in the sRGB colour space.
    VkSurfaceFormatKHR format() const { return format_; }

    // (Re)creates the swapchain for a window of `size` pixels, with framebuffers for `renderPass`.
    // vsync: FIFO; otherwise MAILBOX or IMMEDIATE where offered. Waits until the device is idle.
    void create(VkExtent2D size, VkRenderPass renderPass, bool vsync);

    // The next image, once `acquired` is signalled. False when the swapchain must be recreated.
    bool acquire(VkSemaphore acquired, TargetImage& target);
    // Presents `target` after `renderFinished(target.index)`. False when it must be recreated.
    bool present(const TargetImage& target);
    VkSemaphore renderFinished(std::uint32_t index) const { return images_[index].renderFinished; }

    VkExtent2D extent() const { return extent_; }
    VkPresentModeKHR presentMode() const { return presentMode_; }
    std::uint32_t imageCount() const { return std::uint32_t(images_.size()); }
    std::uint32_t minImageCount() const { return minImageCount_; }
    bool canCopyFrom() const { return canCopyFrom_; }  // screenshots can read its images

private:
    void destroyImages();

    const vk::Context& context_;
    VkSurfaceFormatKHR format_{};
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    std::uint32_t minImageCount_ = 2;
    bool canCopyFrom_ = false;

    struct Image {
        VkImage image = VK_NULL_HANDLE;              // owned by the swapchain
        VkImageView view = VK_NULL_HANDLE;
        VkFramebuffer framebuffer = VK_NULL_HANDLE;
        VkSemaphore renderFinished = VK_NULL_HANDLE; // signalled by the frame, waited for by the present
    };
    std::vector<Image> images_;
};

}  // namespace photon::viewer
