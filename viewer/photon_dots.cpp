#include "photon_dots.h"

#include "glsl/dispatch.h"
#include "glsl/viewer.h"
#include "shared/bindings.h"
#include "vulkan/objects.h"
#include "vulkan/pipelines.h"

namespace photon::viewer {
namespace spirv {
#include "viewer_dots.spv.h"
}  // namespace spirv

PhotonDots::PhotonDots(const vk::Context& context, const vk::VulkanDevice& backend)
    : context_(context), pass_(context.device) {
    VkDevice device = context.device;
    VkDescriptorSetLayoutBinding binding{DOTS_BINDING_DOTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                         VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
    pass_.createSet(&binding, 1);
    // Set 0 is the backend's layout, so that its descriptor set binds here unchanged.
    VkDescriptorSetLayout sets[2] = {backend.pipelines().setLayout, pass_.setLayout};
    pass_.layout = vk::createPipelineLayout(device, sets, 2, {VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(DotsPush)});
    pass_.pipeline = vk::createComputePipeline(context, pass_.layout, spirv::viewer_dots, sizeof(spirv::viewer_dots), "viewer_dots");
    resize(1, 1);
}

// No frame uses the dot buffer when it goes (pass_ waits for the device too, but after it).
PhotonDots::~PhotonDots() { vkDeviceWaitIdle(context_.device); }

void PhotonDots::resize(std::uint32_t width, std::uint32_t height) {
    VkDeviceSize bytes = VkDeviceSize(width) * height * 3 * sizeof(std::uint32_t);
    if (dots_.handle() != VK_NULL_HANDLE && dots_.size() == bytes) {
        return;
    }
    dots_ = vk::Buffer();
    dots_ = vk::Buffer(context_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                       vk::MemoryUse::Device);
    vk::writeBufferDescriptor(context_.device, pass_.set, DOTS_BINDING_DOTS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, dots_.handle(),
                              bytes);
}

void PhotonDots::record(VkCommandBuffer cmd, const vk::VulkanDevice& backend, float brightness, float depthTolerance) {
    // The display pass of the previous frame has read the dots before they are cleared.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                      VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdFillBuffer(cmd, dots_.handle(), 0, VK_WHOLE_SIZE, 0u);
    // The cleared dots are in place before the photons are added to them.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    // One invocation per stored photon of each map, through the group counts that the frame's
    // gridArgs wrote into the counters (its barriers already made them, the photon maps and the
    // hit points visible to later indirect dispatches and compute shaders).
    VkDescriptorSet sets[2] = {backend.pipelines().set, pass_.set};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass_.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pass_.layout, 0, 2, sets, 0, nullptr);
    VkBuffer counters = backend.buffer(BINDING_COUNTERS);
    for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
        DotsPush push{map, brightness, depthTolerance, 0.0f};
        vkCmdPushConstants(cmd, pass_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdDispatchIndirect(cmd, counters, (GRID_ARGS + 3 * map) * sizeof(std::uint32_t));
    }
    // The dots are complete before the display pass's fragment shader reads them.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace photon::viewer
