#version 460
// STAGE_BUILD_GRID, step 2 (down the levels): adds to every cell of a block of gridScan.comp the
// scanned total of the blocks before it.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "glsl/dispatch.h"

layout(local_size_x_id = 0) in;  // the same workgroup size as gridScan.comp

layout(push_constant) uniform Push {
    uint target;     // first cell of the level, in cellStart
    uint count;      // cells of the level
    uint blockSums;  // the scanned block totals, in cellStart
} push;

void main() {
    uint block = workgroupIndex();
    uint offset = cellStart[push.blockSums + block];
    uint blockSize = gl_WorkGroupSize.x * SCAN_ITEMS;
    for (uint k = 0u; k < SCAN_ITEMS; ++k) {
        uint i = block * blockSize + k * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
        if (i < push.count) {
            cellStart[push.target + i] += offset;
        }
    }
}
