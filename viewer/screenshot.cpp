#include "screenshot.h"

#include <cstdint>
#include <vector>


#include "core/image/image.h"
#include "core/system/error.h"

namespace photon::viewer {
namespace {

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                  VkPipelineStageFlags dstStage, VkAccessFlags dstAccess, VkImageLayout oldLayout, VkImageLayout newLayout) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = srcAccess;
    barrier.dstAccessMask = dstAccess;
    barrier.oldLayout = oldLayout;
    barrier.newLayout = newLayout;
    barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, srcStage, dstStage, 0, 0, nullptr, 0, nullptr, 1, &barrier);
}

}  // namespace

void Screenshot::record(VkCommandBuffer cmd, const TargetImage& target, VkFormat format, VkImageLayout layout) {
    VkDeviceSize bytes = VkDeviceSize(target.extent.width) * target.extent.height * 4;
    if (pixels_.size() != bytes) {
        pixels_ = vk::Buffer();
        pixels_ = vk::Buffer(context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, vk::MemoryUse::Readback);
    }
    extent_ = target.extent;
    format_ = format;
    // The image goes to the layout the copy reads (if it is not there already) after the display
    // pass's writes and final transition, which the render pass made available to transfers.
    imageBarrier(cmd, target.image, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                 VK_ACCESS_TRANSFER_READ_BIT, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {target.extent.width, target.extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pixels_.handle(), 1, &region);
    // The copy is done before the image goes back (to be presented, or drawn by the next frame).
    imageBarrier(cmd, target.image, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
    // The copy is written before the host reads it.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_HOST_READ_BIT);
}

void Screenshot::save(const std::string& path) const {
    if (pixels_.mapped() == nullptr) {
        throw RuntimeError("no frame was copied for a screenshot");
    }
    const auto* bgra = static_cast<const std::uint8_t*>(pixels_.mapped());
    bool swap = format_ == VK_FORMAT_B8G8R8A8_UNORM;  // else R8G8B8A8_UNORM
    std::vector<std::uint8_t> rgb(std::size_t(extent_.width) * extent_.height * 3);
    for (std::size_t i = 0; i < std::size_t(extent_.width) * extent_.height; ++i) {
        rgb[3 * i + 0] = bgra[4 * i + (swap ? 2 : 0)];
        rgb[3 * i + 1] = bgra[4 * i + 1];
        rgb[3 * i + 2] = bgra[4 * i + (swap ? 0 : 2)];
    }
    writeRgb8Png(path, rgb.data(), extent_.width, extent_.height);
}

}  // namespace photon::viewer
