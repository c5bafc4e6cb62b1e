// The Vulkan backend's buffers, its frame submission and its readbacks. The frame's commands
// are in record_frame.cpp.
#include "device.h"

#include <algorithm>

#include "check.h"
#include "core/system/error.h"
#include "glsl/dispatch.h"
#include "objects.h"

namespace photon::vk {

VulkanDevice::VulkanDevice(std::shared_ptr<Context> context)
    : context_(std::move(context)), transfers_(*context_), pipelines_(*context_) {
    VkDevice device = context_->device;
    CommandBuffer commands = createCommandBuffer(device, context_->queueFamily);
    frame_.pool = commands.pool;
    frame_.cmd = commands.cmd;
    frame_.done = createFence(device);
    VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
    queryInfo.queryCount = kTimestampCount;
    VK_CHECK(vkCreateQueryPool(device, &queryInfo, nullptr, &frame_.timestamps));
    frame_.counters = Buffer(*context_, COUNTER_COUNT * sizeof(std::uint32_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                             MemoryUse::Readback);
    context_->checkValidation("creating the Vulkan backend");
}

VulkanDevice::~VulkanDevice() {
    VkDevice device = context_->device;
    vkDeviceWaitIdle(device);
    vkDestroyQueryPool(device, frame_.timestamps, nullptr);
    vkDestroyFence(device, frame_.done, nullptr);
    vkDestroyCommandPool(device, frame_.pool, nullptr);
}

void VulkanDevice::ensureBuffer(std::uint32_t binding, VkDeviceSize bytes) {
    Buffer& buffer = buffers_[binding];
    if (buffer.handle() != VK_NULL_HANDLE && buffer.size() == bytes) {
        return;
    }
    VK_CHECK(vkQueueWaitIdle(context_->queue));  // nothing may still use the old buffer
    buffer = Buffer();
    buffer = Buffer(*context_, bytes, bufferUsage(binding), MemoryUse::Device);
    pipelines_.writeDescriptor(binding, buffer.handle(), bytes);
    cellCountsDirty_ = cellCountsDirty_ || binding == BINDING_CELL_COUNTS;
}

MemoryLimits VulkanDevice::memoryLimits() { return deviceMemoryLimits(*context_); }

// The counters buffer also holds the grid build's indirect-dispatch arguments, and cellStart the
// upper levels of the scan.
void VulkanDevice::adjustPlan(BufferPlan& plan, const PhotonBudget& budget) {
    plan.elements[BINDING_COUNTERS] = COUNTER_WORDS;
    plan.elements[BINDING_CELL_START] = planScan(budget, pipelines_.scanGroupSize).cellStartEntries;
    plan.scratchBytes = 0;
}

// Scene arrays to their bindings; an empty array still gets a buffer of one zeroed element.
void VulkanDevice::uploadScene(const Scene& scene, const BufferPlan& plan) {
    forEachSceneBuffer(scene, plan, [&](std::uint32_t binding, const void* data, std::uint64_t bytes) {
        ensureBuffer(binding, bytes);
        transfers_.upload(buffers_[binding], data, bytes);
    });
    context_->checkValidation("uploading the scene");
}

// Every frame buffer, as the plan sizes it. Buffers whose size is unchanged are kept, so a grown
// photon map keeps the accumulated image.
void VulkanDevice::allocate(const BufferPlan& plan, const PhotonBudget& budget, std::uint32_t, std::uint32_t) {
    scan_ = planScan(budget, pipelines_.scanGroupSize);
    ensureBuffer(BINDING_PARAMS, plan.bytes(BINDING_PARAMS));
    for (const BufferInfo& info : kBuffers) {
        if (info.size != BUFFER_PER_SCENE) {
            ensureBuffer(info.binding, plan.bytes(info.binding));
        }
    }
    context_->checkValidation("allocating the frame buffers");
}

void VulkanDevice::beginStages(const FrameParams& params, bool resume) {
    frame_.submitted = false;
    frame_.recording = external_ != VK_NULL_HANDLE ? external_ : frame_.cmd;
    if (external_ == VK_NULL_HANDLE) {
        VK_CHECK(vkResetCommandBuffer(frame_.cmd, 0));
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        VK_CHECK(vkBeginCommandBuffer(frame_.cmd, &begin));
    }
    recordFrameStart(frame_.recording, params, resume);
}

void VulkanDevice::runStage(std::uint32_t stage, const FrameParams& params) { recordStage(frame_.recording, stage, params); }

void VulkanDevice::skipStage(std::uint32_t stage) { timestamp(frame_.recording, stage + 1); }

// The caller's command buffer is the caller's to submit (recordInto()).
void VulkanDevice::submitStages() {
    if (external_ != VK_NULL_HANDLE) {
        external_ = VK_NULL_HANDLE;
        return;
    }
    VkCommandBuffer cmd = frame_.cmd;
    recordStatsReadback(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(context_->queue, 1, &submit, frame_.done));
    frame_.submitted = true;
}

FrameResult VulkanDevice::endStages() {
    if (!frame_.submitted) {
        submitStages();
    }
    VK_CHECK(vkWaitForFences(context_->device, 1, &frame_.done, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(context_->device, 1, &frame_.done));
    frame_.submitted = false;
    return frameResult();
}

void VulkanDevice::recordStatsReadback(VkCommandBuffer cmd) {
    // The counters are final before they are copied out for the host (after the last stage, so
    // the copy delays nothing).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_READ_BIT);
    VkBufferCopy region{0, 0, COUNTER_COUNT * sizeof(std::uint32_t)};
    vkCmdCopyBuffer(cmd, buffers_[BINDING_COUNTERS].handle(), frame_.counters.handle(), 1, &region);
    // The copy is written before the host reads it.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                  VK_ACCESS_HOST_READ_BIT);
}

FrameResult VulkanDevice::frameResult() {
    FrameResult stats;
    const auto* counters = static_cast<const std::uint32_t*>(frame_.counters.mapped());
    std::copy(counters, counters + COUNTER_COUNT, stats.counters);
    if (context_->timestampValidBits > 0) {
        std::uint64_t ticks[kTimestampCount] = {};
        VK_CHECK(vkGetQueryPoolResults(context_->device, frame_.timestamps, 0, kTimestampCount, sizeof(ticks), ticks,
                                       sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        std::uint64_t mask = context_->timestampValidBits >= 64 ? ~0ull : (1ull << context_->timestampValidBits) - 1;
        double msPerTick = double(context_->properties.limits.timestampPeriod) * 1e-6;
        auto ms = [&](std::uint32_t i) { return double((ticks[i + 1] - ticks[i]) & mask) * msPerTick; };
        for (std::uint32_t stage = 0; stage < STAGE_COUNT; ++stage) {
            stats.ms[stage] = ms(stage);
        }
    }
    context_->checkValidation("a frame");
    return stats;
}

void VulkanDevice::readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) {
    transfers_.download(buffers_[binding], offset, data, bytes);
    context_->checkValidation("reading a buffer back");
}

void VulkanDevice::writeBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, const void* data) {
    transfers_.upload(buffers_[binding], data, bytes, offset);
    context_->checkValidation("writing a buffer");
}

}  // namespace photon::vk
