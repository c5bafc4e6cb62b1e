#version 460
// STAGE_BUILD_GRID, step 2: one level of the exclusive prefix sum of the cell counts (Blelloch's
// work-efficient scan, with subgroups doing the in-register part). Each workgroup scans one block
// of SCAN_ITEMS × workgroup-size cells: every invocation sums its SCAN_ITEMS cells, a subgroup
// scan gives each invocation the sum of those before it in its subgroup, the first subgroup then
// scans the subgroup totals, and each cell gets its offset. The block's total goes to blockSums;
// the host scans those with this same shader (the next level) and adds them back with
// gridScanAdd.comp. Nothing here assumes a subgroup size.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "shared/bindings.h"
#include "glsl/dispatch.h"

// The host picks the workgroup size (subgroup size squared, within the device's limit) and
// creates the pipeline with full subgroups required.
layout(local_size_x_id = 0) in;

layout(push_constant) uniform Push {
    uint source;      // first cell of this level: in cellCounts (level 0) or in cellStart
    uint target;      // where the exclusive sums go, in cellStart (may equal source)
    uint count;       // cells of this level
    uint blockSums;   // where each workgroup's total goes, in cellStart
    uint fromCounts;  // 1: the level reads cellCounts (level 0), 0: cellStart
} push;

shared uint subgroupSums[gl_WorkGroupSize.x];  // room for the smallest subgroups (size 1)

void main() {
    // Invocations numbered subgroup by subgroup, so that each subgroup owns consecutive cells.
    uint thread = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    uint first = (workgroupIndex() * gl_WorkGroupSize.x + thread) * SCAN_ITEMS;
    uint items[SCAN_ITEMS];
    uint sum = 0u;
    for (uint k = 0u; k < SCAN_ITEMS; ++k) {
        uint i = first + k;
        uint value = 0u;
        if (i < push.count) {
            value = push.fromCounts != 0u ? cellCounts[push.source + i] : cellStart[push.source + i];
        }
        items[k] = value;
        sum += value;
    }

    uint before = subgroupExclusiveAdd(sum);
    if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) {
        subgroupSums[gl_SubgroupID] = before + sum;
    }
    barrier();

    // The first subgroup turns the subgroup totals into their exclusive sums, a subgroup's
    // width at a time.
    if (gl_SubgroupID == 0u) {
        uint carry = 0u;
        for (uint base = 0u; base < gl_NumSubgroups; base += gl_SubgroupSize) {
            uint s = base + gl_SubgroupInvocationID;
            uint total = s < gl_NumSubgroups ? subgroupSums[s] : 0u;
            uint exclusive = subgroupExclusiveAdd(total);
            if (s < gl_NumSubgroups) {
                subgroupSums[s] = carry + exclusive;
            }
            carry += subgroupAdd(total);
        }
    }
    barrier();

    uint running = subgroupSums[gl_SubgroupID] + before;
    for (uint k = 0u; k < SCAN_ITEMS; ++k) {
        uint i = first + k;
        if (i < push.count) {
            cellStart[push.target + i] = running;
        }
        running += items[k];
    }
    if (thread == gl_WorkGroupSize.x - 1u) {
        cellStart[push.blockSums + workgroupIndex()] = running;
    }
}
