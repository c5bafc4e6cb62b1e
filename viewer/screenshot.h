// Screenshots: the target image as drawn, copied into a host-visible buffer at the end of the
// frame and written as PNG once the frame has run. Shows exactly what was presented (8-bit sRGB).
#pragma once

#include <string>

#include <vulkan/vulkan.h>

#include "target.h"
#include "vulkan/memory.h"

namespace photon::viewer {

class Screenshot {
public:
    explicit Screenshot(const vk::Context& context) : context_(context) {}

    // After the display pass in the same command buffer: copies `target`, which the pass left in
    // `layout`, and leaves it in that layout again.
    void record(VkCommandBuffer cmd, const TargetImage& target, VkFormat format, VkImageLayout layout);
    // Once the frame's commands have completed: writes the copy to `path` (PNG).
    void save(const std::string& path) const;

private:
    const vk::Context& context_;
    vk::Buffer pixels_;  // the copy: 4 bytes per pixel
    VkExtent2D extent_{};
    VkFormat format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace photon::viewer
