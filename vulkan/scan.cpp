// Levels of the multi-level scan, and their dispatches.
#include "scan.h"

#include <algorithm>

#include "glsl/dispatch.h"
#include "memory.h"

namespace photon::vk {

ScanPlan planScan(const PhotonBudget& budget, std::uint32_t groupSize) {
    ScanPlan plan;
    plan.groupSize = groupSize;
    plan.blockSize = groupSize * SCAN_ITEMS;
    std::uint64_t next = budget.totalCellEntries();  // the first free entry of cellStart
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        ScanLevel level;
        level.source = budget.cellOffset(m);
        level.target = budget.cellOffset(m);
        level.count = budget.cells[m] + 1;  // the extra entry ends up holding the map's total
        level.fromCounts = true;
        plan.levels[m].push_back(level);
        while (level.count > 1) {
            level.count = (level.count + plan.blockSize - 1) / plan.blockSize;
            level.source = std::uint32_t(next);
            level.target = std::uint32_t(next);
            level.fromCounts = false;
            plan.levels[m].push_back(level);
            next += level.count;
        }
    }
    plan.cellStartEntries = next;
    return plan;
}

void recordScan(VkCommandBuffer cmd, const Pipelines& pipelines, const ScanPlan& plan) {
    std::size_t depth = 0;
    for (const std::vector<ScanLevel>& levels : plan.levels) {
        depth = std::max(depth, levels.size());
    }

    // Up: scan level j in blocks, each block's total into level j + 1.
    for (std::size_t j = 0; j + 1 < depth; ++j) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.pipeline[kGridScan]);
        for (const std::vector<ScanLevel>& levels : plan.levels) {
            if (j + 1 >= levels.size()) {
                continue;
            }
            const ScanLevel& level = levels[j];
            std::uint32_t push[5] = {level.source, level.target, level.count, levels[j + 1].target,
                                     level.fromCounts ? 1u : 0u};
            vkCmdPushConstants(cmd, pipelines.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
            GroupCount groups = groupsFor(level.count, plan.blockSize);
            vkCmdDispatch(cmd, groups.x, groups.y, 1);
        }
        // Level j's sums and block totals are written before level j + 1 is scanned in place.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    }

    // Down: once level j + 1 is complete (a single block, or its own offsets added), each block
    // of level j gets the total of the blocks before it. A map's two highest levels need nothing.
    for (std::size_t j = depth; j-- > 0;) {
        bool any = false;
        for (const std::vector<ScanLevel>& levels : plan.levels) {
            if (j + 3 > levels.size()) {
                continue;
            }
            if (!any) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelines.pipeline[kGridScanAdd]);
                any = true;
            }
            const ScanLevel& level = levels[j];
            std::uint32_t push[3] = {level.target, level.count, levels[j + 1].target};
            vkCmdPushConstants(cmd, pipelines.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), push);
            GroupCount groups = groupsFor(level.count, plan.blockSize);
            vkCmdDispatch(cmd, groups.x, groups.y, 1);
        }
        if (any) {
            // Level j is complete before the level below reads it (or, for level 0, the scatter).
            memoryBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        }
    }
}

}  // namespace photon::vk
