// The Vulkan backend's buffers, its frame submission and its readbacks. The frame's commands
// are in record_frame.cpp.
#include "backend.h"

#include <algorithm>
#include <cstring>

#include "check.h"
#include "glsl/dispatch.h"
#include "objects.h"

namespace photon::vk {

VulkanBackend::VulkanBackend(std::shared_ptr<Context> context)
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

VulkanBackend::~VulkanBackend() {
    VkDevice device = context_->device;
    vkDeviceWaitIdle(device);
    vkDestroyQueryPool(device, frame_.timestamps, nullptr);
    vkDestroyFence(device, frame_.done, nullptr);
    vkDestroyCommandPool(device, frame_.pool, nullptr);
}

void VulkanBackend::ensureBuffer(std::uint32_t binding, VkDeviceSize bytes) {
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

// Scene arrays to their bindings; an empty array still gets a buffer of one zeroed element.
void VulkanBackend::uploadScene(const Scene& scene) {
    struct Array {
        std::uint32_t binding;
        const void* data;
        std::size_t count;
        std::size_t elementBytes;
    };
    const Array arrays[] = {
        {BINDING_SPHERES, scene.spheres.data(), scene.spheres.size(), sizeof(Sphere)},
        {BINDING_PLANES, scene.planes.data(), scene.planes.size(), sizeof(Plane)},
        {BINDING_QUADS, scene.quads.data(), scene.quads.size(), sizeof(Quad)},
        {BINDING_TRIANGLES, scene.triangles.data(), scene.triangles.size(), sizeof(Triangle)},
        {BINDING_MATERIALS, scene.materials.data(), scene.materials.size(), sizeof(Material)},
        {BINDING_LIGHTS, scene.lights.data(), scene.lights.size(), sizeof(Light)},
        {BINDING_TARGETS, scene.targets.data(), scene.targets.size(), sizeof(CausticTarget)},
    };
    for (const Array& a : arrays) {
        plan_.bytes[a.binding] = VkDeviceSize(std::max<std::size_t>(a.count, 1)) * a.elementBytes;
    }
    checkLimits(*context_, plan_, width_, height_);
    for (const Array& a : arrays) {
        VkDeviceSize bytes = plan_.bytes[a.binding];
        ensureBuffer(a.binding, bytes);
        std::vector<unsigned char> data(bytes, 0);
        if (a.count > 0) {
            std::memcpy(data.data(), a.data, a.count * a.elementBytes);
        }
        transfers_.upload(buffers_[a.binding], data.data(), bytes);
    }
    context_->checkValidation("uploading the scene");
}

// Every frame buffer, sized for the budget and image; limits are checked before anything is
// allocated. Buffers whose size is unchanged are kept, so a grown photon map keeps the
// accumulated image.
void VulkanBackend::allocate(const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) {
    BufferPlan plan = planBuffers(budget, width, height, pipelines_.scanGroupSize);
    for (std::uint32_t b = BINDING_SPHERES; b <= BINDING_TARGETS; ++b) {
        plan.bytes[b] = plan_.bytes[b];
    }
    checkLimits(*context_, plan, width, height);
    plan_ = plan;
    width_ = width;
    height_ = height;
    for (std::uint32_t b = 0; b < BINDING_COUNT; ++b) {
        if (b < BINDING_SPHERES || b > BINDING_TARGETS) {
            ensureBuffer(b, plan.bytes[b]);
        }
    }
    context_->checkValidation("allocating the frame buffers");
}

FrameStats VulkanBackend::runFrame(const FrameParams& params) {
    VkCommandBuffer cmd = frame_.cmd;
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    recordFrame(cmd, params);
    recordStatsReadback(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));

    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    VK_CHECK(vkQueueSubmit(context_->queue, 1, &submit, frame_.done));
    VK_CHECK(vkWaitForFences(context_->device, 1, &frame_.done, VK_TRUE, UINT64_MAX));
    VK_CHECK(vkResetFences(context_->device, 1, &frame_.done));
    return frameStats(params);
}

void VulkanBackend::recordStatsReadback(VkCommandBuffer cmd) {
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

FrameStats VulkanBackend::frameStats(const FrameParams& params) {
    FrameStats stats;
    const auto* counters = static_cast<const std::uint32_t*>(frame_.counters.mapped());
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        std::uint32_t counter = counters[m == MAP_GLOBAL ? COUNTER_STORED_GLOBAL : COUNTER_STORED_CAUSTIC];
        stats.stored[m] = counter;
        stats.capacity[m] = params.grids[m].photonCapacity;
        stored_[m] = std::min(counter, params.grids[m].photonCapacity);
    }
    stats.emitted[MAP_GLOBAL] = params.globalPaths;
    stats.emitted[MAP_CAUSTIC] = params.causticPaths;
    if (context_->timestampValidBits > 0) {
        std::uint64_t ticks[kTimestampCount] = {};
        VK_CHECK(vkGetQueryPoolResults(context_->device, frame_.timestamps, 0, kTimestampCount, sizeof(ticks), ticks,
                                       sizeof(std::uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
        std::uint64_t mask = context_->timestampValidBits >= 64 ? ~0ull : (1ull << context_->timestampValidBits) - 1;
        double msPerTick = double(context_->properties.limits.timestampPeriod) * 1e-6;
        auto ms = [&](std::uint32_t i) { return double((ticks[i + 1] - ticks[i]) & mask) * msPerTick; };
        stats.ms.tracePhotons = ms(0);
        stats.ms.buildGrid = ms(1);
        stats.ms.tracePixels = ms(2);
        stats.ms.gather = ms(3);
        stats.ms.accumulate = ms(4);
    }
    context_->checkValidation("a frame");
    return stats;
}

PhotonMaps VulkanBackend::readPhotonMaps() {
    PhotonMaps maps;
    const FrameParams& params = lastFrameParams();
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        const GridParams& grid = params.grids[m];
        maps.photons[m].resize(stored_[m]);
        transfers_.download(buffers_[BINDING_SORTED_PHOTONS], VkDeviceSize(grid.photonOffset) * sizeof(Photon),
                            maps.photons[m].data(), VkDeviceSize(stored_[m]) * sizeof(Photon));
        maps.cellStart[m].resize(std::size_t(grid.cellCount) + 1);
        transfers_.download(buffers_[BINDING_CELL_START], VkDeviceSize(grid.cellOffset) * sizeof(std::uint32_t),
                            maps.cellStart[m].data(), maps.cellStart[m].size() * sizeof(std::uint32_t));
    }
    context_->checkValidation("reading the photon maps");
    return maps;
}

std::vector<HitPoint> VulkanBackend::readHitPoints() {
    std::vector<HitPoint> hitPoints(std::size_t(width_) * height_);
    transfers_.download(buffers_[BINDING_HIT_POINTS], 0, hitPoints.data(), hitPoints.size() * sizeof(HitPoint));
    context_->checkValidation("reading the hit points");
    return hitPoints;
}

Image VulkanBackend::readImage(std::uint32_t binding) {
    Image image(width_, height_);
    transfers_.download(buffers_[binding], 0, image.pixels.data(), image.pixels.size() * sizeof(glm::vec4));
    context_->checkValidation("reading an image");
    return image;
}

Image VulkanBackend::readFrame() { return readImage(BINDING_FRAME); }

Image VulkanBackend::readAccumulation() { return readImage(BINDING_ACCUMULATION); }

}  // namespace photon::vk
