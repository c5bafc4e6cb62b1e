// One frame as commands: the parameters, then the stages of shared/stages.h in the order the
// Renderer runs them, each with the barrier that orders its writes before the next stage's reads,
// and a timestamp after it.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "device.h"
#include "glsl/dispatch.h"
#include "shared/medium.h"
#include "shared/progressive.h"

namespace photon::vk {

void VulkanDevice::recordFrameStart(VkCommandBuffer cmd, const FrameParams& params, bool resume) {
    Pipelines& p = pipelines_;
    if (context_->timestampValidBits > 0) {
        vkCmdResetQueryPool(cmd, frame_.timestamps, 0, kTimestampCount);
    }
    timestamp(cmd, 0);

    // The previous frame (and any readback) is done with the parameters and counters before this
    // frame rewrites them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdUpdateBuffer(cmd, buffers_[BINDING_PARAMS].handle(), 0, sizeof(FrameParams), &params);
    if (!resume) {
        vkCmdFillBuffer(cmd, buffers_[BINDING_COUNTERS].handle(), 0, COUNTER_COUNT * sizeof(std::uint32_t), 0u);
    }
    if (cellCountsDirty_) {
        vkCmdFillBuffer(cmd, buffers_[BINDING_CELL_COUNTS].handle(), 0, VK_WHOLE_SIZE, 0u);
        cellCountsDirty_ = false;
    }
    // The parameters and the cleared counters are in place before any stage reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0, nullptr);
}

// The stage's commands, by its function below (named as the stage), then timestamp stage + 1.
void VulkanDevice::recordStage(VkCommandBuffer cmd, std::uint32_t stage, const FrameParams& params) {
#define PH_VULKAN_STAGE(NAME, id, name, label) &VulkanDevice::name,
    static constexpr void (VulkanDevice::*kRecord[])(VkCommandBuffer, const FrameParams&) = {PH_STAGES(PH_VULKAN_STAGE)};
    if (stage >= STAGE_COUNT) {
        throw std::logic_error("Vulkan: unknown stage " + std::to_string(stage));
    }
    (this->*kRecord[stage])(cmd, params);
    timestamp(cmd, stage + 1);
}

void VulkanDevice::timestamp(VkCommandBuffer cmd, std::uint32_t index) {
    if (context_->timestampValidBits > 0) {
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, frame_.timestamps, index);
    }
}

// One invocation per pixel, in tiles `tileX` pixels wide.
void VulkanDevice::dispatchPixels(VkCommandBuffer cmd, VkPipeline pipeline, const FrameParams& params, std::uint32_t tileX) {
    std::uint32_t tilesX = (params.width + tileX - 1) / tileX;
    std::uint32_t tilesY = (params.height + PIXEL_TILE_Y - 1) / PIXEL_TILE_Y;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    vkCmdDispatch(cmd, tilesX, tilesY, 1);
}

// The pool over the paths of both passes.
void VulkanDevice::tracePhotons(VkCommandBuffer cmd, const FrameParams& params) {
    GroupCount groups = groupsFor(std::min(params.pathCount, PHOTON_POOL), GROUP_SIZE);
    if (groups.x != 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_.tracing(kTracePhotons, sceneHasMedia(params)));
        vkCmdDispatch(cmd, groups.x, groups.y, 1);
    }
    // The photons and their counters are written before the grid build reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

void VulkanDevice::tracePixels(VkCommandBuffer cmd, const FrameParams& params) {
    dispatchPixels(cmd, pipelines_.tracing(kTracePixels, sceneHasMedia(params)), params, EYE_TILE_X);
    // The hit points are written before gather reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

// The passes in order, the restore pass reading what save wrote of other pixels.
void VulkanDevice::reproject(VkCommandBuffer cmd, const FrameParams& params) {
    if ((params.flags & FLAG_REPROJECT) == 0u) {
        return;
    }
    dispatchPasses(cmd, kReproject, REPROJECT_PASS_COUNT, params);
    // The carried histories are written before gather and accumulate read them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
}

// Passes of one shader over the pixels, in order, each after the one before has written (the
// pass number as push constant).
void VulkanDevice::dispatchPasses(VkCommandBuffer cmd, Shader shader, std::uint32_t passes, const FrameParams& params) {
    for (std::uint32_t pass = 0; pass < passes; ++pass) {
        if (pass > 0) {
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        }
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_.pipeline[shader]);
        vkCmdPushConstants(cmd, pipelines_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pass), &pass);
        std::uint32_t tilesX = (params.width + PIXEL_TILE_X - 1) / PIXEL_TILE_X;
        std::uint32_t tilesY = (params.height + PIXEL_TILE_Y - 1) / PIXEL_TILE_Y;
        vkCmdDispatch(cmd, tilesX, tilesY, 1);
    }
}

// With the pipeline of the frame's estimator and mode.
void VulkanDevice::gather(VkCommandBuffer cmd, const FrameParams& params) {
    dispatchPixels(cmd, pipelines_.gather(params.estimator, params.globalMode,
                                          sppmStarts(params.estimator, params.view, params.accumulated)),
                   params, PIXEL_TILE_X);
    // This frame's radiance is written before accumulate reads it.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

void VulkanDevice::accumulate(VkCommandBuffer cmd, const FrameParams& params) {
    dispatchPixels(cmd, pipelines_.pipeline[kAccumulate], params, PIXEL_TILE_X);
    // The running mean and the auxiliary images are written before denoise reads them; the
    // caller orders its own reads of the accumulation (recordInto()).
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

// The passes in order, each reading what the one before wrote. The last writes `denoised`: the
// caller orders its own reads of it.
void VulkanDevice::denoise(VkCommandBuffer cmd, const FrameParams& params) {
    if ((params.flags & FLAG_DENOISE) == 0u) {
        return;
    }
    dispatchPasses(cmd, kDenoise, DENOISE_PASS_COUNT, params);
}

// A counting sort of each map's photons by cell. The count and scatter passes run over the photons
// actually stored, through group counts that gridArgs writes from the counters.
void VulkanDevice::buildGrid(VkCommandBuffer cmd, const FrameParams& params) {
    const Pipelines& p = pipelines_;
    VkBuffer counters = buffers_[BINDING_COUNTERS].handle();
    auto dispatchPerMap = [&](Shader shader) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline[shader]);
        for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
            vkCmdPushConstants(cmd, p.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(map), &map);
            vkCmdDispatchIndirect(cmd, counters, (GRID_ARGS + 3 * map) * sizeof(std::uint32_t));
        }
    };

    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline[kGridArgs]);
    vkCmdDispatch(cmd, 1, 1, 1);
    // The group counts are written before the indirect dispatches read them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_SHADER_READ_BIT);

    dispatchPerMap(kGridCount);
    // Every photon's key and its cell's count are in place before the scan reads the counts.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    recordScan(cmd, p, scan_);
    // The cell starts are written, and the scan has read the counts, before the scatter reads the
    // starts and counts the counts back down.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);

    if ((params.flags & FLAG_DETERMINISTIC) != 0u) {
        // Each cell's photons in canonical order (shared/photon_map.h): each step reads what the
        // one before wrote.
        dispatchPerMap(kGridScatterIds);
        for (Shader step : {kGridRank, kGridMerge}) {
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
            dispatchPerMap(step);
        }
    } else {
        dispatchPerMap(kGridScatter);
    }
    // The photon maps are complete before gather reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace photon::vk
