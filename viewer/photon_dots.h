// Photon dots, Wu's picture of the photon maps: after the backend's frame, every stored
// photon of both maps is projected to the screen and added to its pixel, weighted by its power
// (glsl/viewer_dots.comp). The pass reads the backend's buffers through the backend's own
// descriptor set (set 0 of its layout) and writes a dot buffer of its own (set 1), which the
// display pass then shows in place of the image.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

#include "pass_pipeline.h"
#include "vulkan/device.h"
#include "vulkan/memory.h"
#include "vulkan/non_copyable.h"

namespace photon::viewer {

class PhotonDots : vk::NonCopyable {
public:
    PhotonDots(const vk::Context& context, const vk::VulkanDevice& backend);
    ~PhotonDots();

    // Sizes the dot buffer for a width × height image (three uint per pixel). Only while no
    // submitted frame uses it.
    void resize(std::uint32_t width, std::uint32_t height);
    VkBuffer buffer() const { return dots_.handle(); }

    // Clears the dots and draws this frame's photons. After the backend's recordFrame() in the
    // same command buffer; `brightness` is per watt of photon power; `depthTolerance` 0 shows
    // hidden photons too. Leaves the dots written for the fragment shader to read.
    void record(VkCommandBuffer cmd, const vk::VulkanDevice& backend, float brightness, float depthTolerance);

private:
    const vk::Context& context_;
    PassPipeline pass_;  // the set of the dot buffer; the layout: the backend's set, ours, DotsPush
    vk::Buffer dots_;    // three fixed-point uint per pixel
};

}  // namespace photon::viewer
