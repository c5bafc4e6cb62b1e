// The Vulkan backend: the five stages as compute shaders (glsl/) over the shared core, one
// command buffer and one submission per frame. Headless programs reach it through
// createVulkanBackend(); a windowed viewer builds its own Context (with surface and swapchain
// extensions), constructs the backend on it, records frames into its own command buffers with
// recordFrame() and presents from accumulationBuffer().
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "buffer_plan.h"
#include "scan.h"
#include "context.h"
#include "core/backend.h"
#include "memory.h"
#include "photon_sort.h"
#include "pipelines.h"

namespace photon::vk {

// Timestamps around the stages: before tracePhotons, then after each of the five.
constexpr std::uint32_t kTimestampCount = 6;

class VulkanBackend final : public Backend {
public:
    explicit VulkanBackend(std::shared_ptr<Context> context);
    ~VulkanBackend() override;

    std::string name() const override { return "vulkan"; }
    std::string deviceName() const override { return context_->properties.deviceName; }

    MemoryLimits memoryLimits() override;

    // Records a whole frame into `cmd`: its parameters, the stages and the barriers between them,
    // and timestamps. Call prepare() first. The frame starts with a barrier against everything
    // earlier on the queue and ends with accumulation written by a compute shader: the caller
    // orders its own reads of it (COMPUTE_SHADER / SHADER_WRITE before them).
    void recordFrame(VkCommandBuffer cmd, const FrameParams& params);

    // After recordFrame() in the caller's command buffer: copies the frame's counters for the
    // host. Once that submission has completed, frameResult() reads them and the stage timestamps
    // (what runFrame() returns). One frame at a time: there is one copy and one query pool.
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

protected:
    void adjustPlan(BufferPlan& plan, const PhotonBudget& budget) override;
    void uploadScene(const Scene& scene, const BufferPlan& plan) override;
    void allocate(const BufferPlan& plan, const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) override;
    FrameResult runFrame(const FrameParams& params) override;
    void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) override;

private:
    // (Re)creates the buffer of `binding` if its size changed and points the descriptor at it.
    void ensureBuffer(std::uint32_t binding, VkDeviceSize bytes);
    void recordBuildGrid(VkCommandBuffer cmd, const FrameParams& params);

    // Device, one-off copies, pipelines.
    std::shared_ptr<Context> context_;  // shared with a viewer, if any; outlives everything below
    Transfers transfers_;               // uploads and readbacks, waited for
    Pipelines pipelines_;               // every shader, one descriptor set

    // Buffers by binding number (shared/bindings.h), device-local.
    Buffer buffers_[BINDING_COUNT];
    ScanPlan scan_;              // the levels of the cell-count scan, in cellStart
    std::unique_ptr<PhotonSort> sort_;  // the deterministic build's, made on first use

    // The frame runFrame() submits.
    struct Frame {
        VkCommandPool pool = VK_NULL_HANDLE;      // owns cmd
        VkCommandBuffer cmd = VK_NULL_HANDLE;     // re-recorded every frame
        VkFence done = VK_NULL_HANDLE;            // signalled when the frame has run
        VkQueryPool timestamps = VK_NULL_HANDLE;  // kTimestampCount timestamps around the stages
        Buffer counters;                          // host-visible copy of the counters after the frame
    } frame_;
    bool cellCountsDirty_ = true;  // a new cell-count buffer must be zeroed once; after that the
                                   // scatter leaves it at zero every frame
};

}  // namespace photon::vk
