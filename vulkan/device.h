// The Vulkan device: the stages as compute shaders (glsl/) over the shared core, one command
// buffer and one submission per frame. Headless programs reach it through createVulkanDevice(); a
// windowed viewer builds its own Context (with surface and swapchain extensions), constructs the
// device on it, has the Renderer record frames into its own command buffers (recordInto(),
// Renderer::recordFrame()) and presents from accumulationBuffer().
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer_plan.h"
#include "context.h"
#include "core/frame/device.h"
#include "memory.h"
#include "pipelines.h"
#include "scan.h"

namespace photon::vk {

// Timestamps around the stages: before the first, then after each.
constexpr std::uint32_t kTimestampCount = STAGE_COUNT + 1;

class VulkanDevice final : public Device {
public:
    explicit VulkanDevice(std::shared_ptr<Context> context);
    ~VulkanDevice() override;

    std::string name() const override { return "vulkan"; }
    std::string deviceName() const override { return context_->properties.deviceName; }
    bool runsOnCpu() const override { return context_->properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }

    MemoryLimits memoryLimits() override;

    // The next frame's stages (beginStages() to submitStages(), as Renderer::recordFrame() runs
    // them) go into the caller's command buffer `cmd` instead of the device's own, for the caller
    // to submit. The frame starts with a barrier against everything earlier on the queue and ends
    // with accumulation written by a compute shader: the caller orders its own reads of it
    // (COMPUTE_SHADER / SHADER_WRITE before them).
    void recordInto(VkCommandBuffer cmd) { external_ = cmd; }

    // After a frame recorded into the caller's command buffer: copies the frame's counters for the
    // host. Once that submission has completed, frameResult() reads them and the stage timestamps
    // (what endStages() returns). One frame at a time: there is one copy and one query pool.
    void recordStatsReadback(VkCommandBuffer cmd);
    FrameResult frameResult();

    // The running mean: width × height vec4 of linear radiance, row by row from the top.
    VkBuffer accumulationBuffer() const { return buffers_[BINDING_ACCUMULATION].handle(); }
    // Any buffer of shared/bindings.h, and the descriptor set that binds them all (set 0 of
    // pipelines().layout), for a viewer's own passes over the frame's data (e.g. the photon maps).
    // Both change when prepare() reallocates: look them up after it, for each frame.
    VkBuffer buffer(std::uint32_t binding) const { return buffers_[binding].handle(); }
    const Pipelines& pipelines() const { return pipelines_; }
    const Context& context() const { return *context_; }

    void adjustPlan(BufferPlan& plan, const PhotonBudget& budget) override;
    void uploadScene(const Scene& scene, const BufferPlan& plan) override;
    void allocate(const BufferPlan& plan, const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) override;
    // beginStages() starts the frame's command buffer, runStage() records a stage into it,
    // submitStages() submits it, endStages() waits.
    void beginStages(const FrameParams& params, bool resume) override;
    void runStage(std::uint32_t stage, const FrameParams& params) override;
    void skipStage(std::uint32_t stage) override;
    void submitStages() override;
    FrameResult endStages() override;
    void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) override;
    void writeBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, const void* data) override;

private:
    // (Re)creates the buffer of `binding` if its size changed and points the descriptor at it.
    void ensureBuffer(std::uint32_t binding, VkDeviceSize bytes);
    // The parameters and cleared counters (unless resuming), before the first stage (record_frame.cpp).
    void recordFrameStart(VkCommandBuffer cmd, const FrameParams& params, bool resume);
    // One stage with its barrier and timestamp; and each stage's commands, named as the stage.
    void recordStage(VkCommandBuffer cmd, std::uint32_t stage, const FrameParams& params);
#define PH_VULKAN_STAGE_FUNCTION(NAME, id, name, label) void name(VkCommandBuffer cmd, const FrameParams& params);
    PH_STAGES(PH_VULKAN_STAGE_FUNCTION)
    void dispatchPixels(VkCommandBuffer cmd, VkPipeline pipeline, const FrameParams& params, std::uint32_t tileX);
    void dispatchPasses(VkCommandBuffer cmd, Shader shader, std::uint32_t passes, const FrameParams& params);
    void timestamp(VkCommandBuffer cmd, std::uint32_t index);

    // Device, one-off copies, pipelines.
    std::shared_ptr<Context> context_;  // shared with a viewer, if any; outlives everything below
    Transfers transfers_;               // uploads and readbacks, waited for
    Pipelines pipelines_;               // every shader, one descriptor set

    // Buffers by binding number (shared/bindings.h), device-local.
    Buffer buffers_[BINDING_COUNT];
    ScanPlan scan_;              // the levels of the cell-count scan, in cellStart

    // The frame beginStages() records, submitStages() submits and endStages() waits for.
    struct Frame {
        VkCommandPool pool = VK_NULL_HANDLE;      // owns cmd
        VkCommandBuffer cmd = VK_NULL_HANDLE;     // re-recorded every frame
        VkFence done = VK_NULL_HANDLE;            // signalled when the frame has run
        VkQueryPool timestamps = VK_NULL_HANDLE;  // kTimestampCount timestamps around the stages
        Buffer counters;                          // host-visible copy of the counters after the frame
        VkCommandBuffer recording = VK_NULL_HANDLE;  // where the stages go: cmd or a caller's
        bool submitted = false;                   // submitStages() ran; endStages() waits
    } frame_;
    VkCommandBuffer external_ = VK_NULL_HANDLE;  // recordInto()'s, for the next frame only
    bool cellCountsDirty_ = true;  // a new cell-count buffer must be zeroed once; after that the
                                   // scatter leaves it at zero every frame
};

}  // namespace photon::vk
