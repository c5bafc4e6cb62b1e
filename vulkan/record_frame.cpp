// One frame as commands: the parameters, the five stages in order with a barrier between each
// stage and the next, and a timestamp after each.
#include "backend.h"
#include "glsl/dispatch.h"

namespace photon::vk {

void VulkanBackend::recordFrame(VkCommandBuffer cmd, const FrameParams& params) {
    Pipelines& p = pipelines_;
    bool timed = context_->timestampValidBits > 0;
    auto timestamp = [&](std::uint32_t index) {
        if (timed) {
            vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, frame_.timestamps, index);
        }
    };
    if (timed) {
        vkCmdResetQueryPool(cmd, frame_.timestamps, 0, kTimestampCount);
    }
    timestamp(0);

    // The previous frame (and any readback) is done with the parameters and counters before this
    // frame rewrites them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT);
    vkCmdUpdateBuffer(cmd, buffers_[BINDING_PARAMS].handle(), 0, sizeof(FrameParams), &params);
    vkCmdFillBuffer(cmd, buffers_[BINDING_COUNTERS].handle(), 0, COUNTER_COUNT * sizeof(std::uint32_t), 0u);
    if (cellCountsDirty_) {
        vkCmdFillBuffer(cmd, buffers_[BINDING_CELL_COUNTS].handle(), 0, VK_WHOLE_SIZE, 0u);
        cellCountsDirty_ = false;
    }
    // The parameters and the cleared counters are in place before any stage reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                  VK_ACCESS_UNIFORM_READ_BIT | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0, nullptr);

    // tracePhotons: one invocation per path of both passes.
    dispatch(cmd, p, kTracePhotons, params.pathCount, GROUP_SIZE);
    // The photons and their counters are written before the grid build reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    timestamp(1);

    recordBuildGrid(cmd, params);
    timestamp(2);

    // tracePixels: one invocation per pixel, in tiles.
    std::uint32_t tilesX = (params.width + PIXEL_TILE_X - 1) / PIXEL_TILE_X;
    std::uint32_t tilesY = (params.height + PIXEL_TILE_Y - 1) / PIXEL_TILE_Y;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline[kTracePixels]);
    vkCmdDispatch(cmd, tilesX, tilesY, 1);
    // The hit points are written before gather reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    timestamp(3);

    // gather: one invocation per pixel, with the pipeline of the frame's estimator and mode.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines_.gather(params.estimator, params.globalMode));
    vkCmdDispatch(cmd, tilesX, tilesY, 1);
    // This frame's radiance is written before accumulate reads it.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    timestamp(4);

    // accumulate: one invocation per pixel.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline[kAccumulate]);
    vkCmdDispatch(cmd, tilesX, tilesY, 1);
    timestamp(5);
}

// buildGrid: a counting sort of each map's photons by cell. The count and scatter passes run over
// the photons actually stored, through group counts that gridArgs writes from the counters.
void VulkanBackend::recordBuildGrid(VkCommandBuffer cmd, const FrameParams& params) {
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
        // Sorting (cell key, id) instead of the scatter: each cell's photons in canonical order.
        for (std::uint32_t map = 0; map < MAP_COUNT; ++map) {
            sort_->record(cmd, params, map, buffers_[BINDING_CELL_COUNTS].handle());
        }
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0, nullptr);
    } else {
        dispatchPerMap(kGridScatter);
    }
    // The photon maps are complete before gather reads them.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                  VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
}

}  // namespace photon::vk
