// The exclusive prefix sum of each map's cell counts into cellStart, as levels of gridScan.comp:
// level 0 scans the counts in blocks, level 1 scans the block totals of level 0, and so on until
// one block remains; gridScanAdd.comp then adds each level's scanned totals back into the level
// below. The levels above 0 live in cellStart after both maps' cells.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "core/frame/frame_setup.h"
#include "pipelines.h"

namespace photon::vk {

struct ScanLevel {
    std::uint32_t source = 0;     // first element: in cellCounts for level 0, else in cellStart
    std::uint32_t target = 0;     // where its exclusive sums go, in cellStart
    std::uint32_t count = 0;      // elements
    bool fromCounts = false;      // level 0 reads the counts
};

struct ScanPlan {
    std::uint32_t groupSize = 0;                // workgroup of the scan shaders
    std::uint32_t blockSize = 0;                // elements one workgroup scans: groupSize × SCAN_ITEMS
    std::vector<ScanLevel> levels[MAP_COUNT];   // the last level of each map holds one element, its total
    std::uint64_t cellStartEntries = 0;         // cellStart length: both maps' cells + 1 each, then the levels
};

ScanPlan planScan(const PhotonBudget& budget, std::uint32_t groupSize);

// Records the scans of both maps, level by level, with a barrier after each level. The counts
// must be written (and made visible to compute shaders) before.
void recordScan(VkCommandBuffer cmd, const Pipelines& pipelines, const ScanPlan& plan);

}  // namespace photon::vk
