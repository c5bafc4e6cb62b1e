// The display pass: one render pass per frame over the target image, in which a full-screen
// triangle shows the accumulated image (or the photon dots) exposed and tone-mapped, and the
// HUD is drawn on top. A fragment shader rather than a compute shader writing a storage image:
// swapchain images need not allow storage, and one pass then serves the image and the HUD, with
// no extra image and no copy (measured on lavapipe: docs/viewer.md).
#pragma once

#include <vulkan/vulkan.h>

#include "glsl/viewer.h"
#include "pass_pipeline.h"
#include "target.h"
#include "vulkan/context.h"
#include "vulkan/non_copyable.h"

namespace photon::viewer {

class DisplayPass : vk::NonCopyable {
public:
    // finalLayout: where the render pass leaves the target (PRESENT_SRC_KHR for a swapchain).
    DisplayPass(const vk::Context& context, VkFormat format, VkImageLayout finalLayout);
    ~DisplayPass();

    VkRenderPass renderPass() const { return renderPass_; }
    VkImageLayout finalLayout() const { return finalLayout_; }

    // Points the descriptor set at this frame's accumulation buffer and dot buffer. Only while no
    // submitted frame uses it (the viewer calls it after waiting for the previous frame).
    void setSources(VkBuffer image, VkBuffer dots);

    // Begins the render pass over `target` (its old contents discarded) and draws the image.
    void begin(VkCommandBuffer cmd, const TargetImage& target);
    void draw(VkCommandBuffer cmd, const DisplayPush& push);
    void end(VkCommandBuffer cmd);

private:
    void createRenderPass(VkFormat format);
    void createPipeline();

    const vk::Context& context_;
    VkImageLayout finalLayout_;
    VkRenderPass renderPass_ = VK_NULL_HANDLE;
    PassPipeline pass_;  // the set of the two buffers, read by the fragment shader; the layout adds DisplayPush
};

}  // namespace photon::viewer
