#include "pass_pipeline.h"

#include "vulkan/check.h"
#include "vulkan/objects.h"

namespace photon::viewer {

PassPipeline::~PassPipeline() {
    vkDeviceWaitIdle(device);
    vkDestroyPipeline(device, pipeline, nullptr);
    vkDestroyPipelineLayout(device, layout, nullptr);
    vkDestroyDescriptorPool(device, pool, nullptr);
    vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
}

void PassPipeline::createSet(const VkDescriptorSetLayoutBinding* bindings, std::uint32_t count) {
    VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    info.bindingCount = count;
    info.pBindings = bindings;
    VK_CHECK(vkCreateDescriptorSetLayout(device, &info, nullptr, &setLayout));
    vk::SingleDescriptorSet descriptors = vk::allocateSingleSet(device, setLayout, count);
    pool = descriptors.pool;
    set = descriptors.set;
}

}  // namespace photon::viewer
