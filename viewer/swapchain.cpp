// Surface format and present mode, swapchain creation and recreation, acquire and present.
#include "swapchain.h"

#include <algorithm>

#include "core/system/error.h"
#include "vulkan/check.h"

namespace photon::viewer {
namespace {

VkSurfaceFormatKHR chooseFormat(const vk::Context& context) {
    std::uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice, context.surface, &count, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(count);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(context.physicalDevice, context.surface, &count, formats.data()));
    for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
        for (const VkSurfaceFormatKHR& f : formats) {
            if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
                return f;
            }
        }
    }
    throw RuntimeError("the window surface offers no B8G8R8A8_UNORM or R8G8B8A8_UNORM format");
}

VkPresentModeKHR choosePresentMode(const vk::Context& context, bool vsync) {
    if (vsync) {
        return VK_PRESENT_MODE_FIFO_KHR;  // always offered
    }
    std::uint32_t count = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(context.physicalDevice, context.surface, &count, nullptr));
    std::vector<VkPresentModeKHR> modes(count);
    VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(context.physicalDevice, context.surface, &count, modes.data()));
    for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR}) {
        if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) {
            return wanted;
        }
    }
    return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Swapchain::Swapchain(const vk::Context& context) : context_(context), format_(chooseFormat(context)) {}

Swapchain::~Swapchain() {
    vkDeviceWaitIdle(context_.device);
    destroyImages();
    vkDestroySwapchainKHR(context_.device, swapchain_, nullptr);
}

void Swapchain::destroyImages() {
    for (Image& image : images_) {
        vkDestroyFramebuffer(context_.device, image.framebuffer, nullptr);
        vkDestroyImageView(context_.device, image.view, nullptr);
        vkDestroySemaphore(context_.device, image.renderFinished, nullptr);
    }
    images_.clear();
}

void Swapchain::create(VkExtent2D size, VkRenderPass renderPass, bool vsync) {
    VkDevice device = context_.device;
    VK_CHECK(vkDeviceWaitIdle(device));  // nothing may still use the old images
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physicalDevice, context_.surface, &caps));
    // Where the surface says how large it is, that is the size; otherwise the window's.
    extent_ = caps.currentExtent.width != 0xFFFFFFFFu ? caps.currentExtent : size;
    extent_.width = std::clamp(extent_.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height = std::clamp(extent_.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    presentMode_ = choosePresentMode(context_, vsync);
    minImageCount_ = caps.minImageCount + 1;
    if (caps.maxImageCount > 0) {
        minImageCount_ = std::min(minImageCount_, caps.maxImageCount);
    }
    canCopyFrom_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = context_.surface;
    info.minImageCount = minImageCount_;
    info.imageFormat = format_.format;
    info.imageColorSpace = format_.colorSpace;
    info.imageExtent = extent_;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (canCopyFrom_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    info.presentMode = presentMode_;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSwapchainKHR(device, &info, nullptr, &created));
    destroyImages();
    vkDestroySwapchainKHR(device, swapchain_, nullptr);
    swapchain_ = created;

    std::uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, nullptr));
    std::vector<VkImage> images(count);
    VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain_, &count, images.data()));
    images_.resize(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        Image& image = images_[i];
        image.image = images[i];
        image.view = createColorView(device, image.image, format_.format);
        image.framebuffer = createFramebuffer(device, renderPass, image.view, extent_);
        VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VK_CHECK(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &image.renderFinished));
    }
}

bool Swapchain::acquire(VkSemaphore acquired, TargetImage& target) {
    std::uint32_t index = 0;
    VkResult result = vkAcquireNextImageKHR(context_.device, swapchain_, UINT64_MAX, acquired, VK_NULL_HANDLE, &index);
    if (result == VK_ERROR_OUT_OF_DATE_KHR) {
        return false;
    }
    VK_CHECK(result);  // VK_SUBOPTIMAL_KHR still acquired an image: draw it, recreate after presenting
    target.image = images_[index].image;
    target.framebuffer = images_[index].framebuffer;
    target.extent = extent_;
    target.index = index;
    return true;
}

bool Swapchain::present(const TargetImage& target) {
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &images_[target.index].renderFinished;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain_;
    info.pImageIndices = &target.index;
    VkResult result = vkQueuePresentKHR(context_.queue, &info);
    if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) {
        return false;
    }
    VK_CHECK(result);
    return true;
}

}  // namespace photon::viewer
