#version 460
// Deterministic grid build (STAGE_BUILD_GRID), a radix pass's first step: how many keys of each tile have each digit.
#extension GL_GOOGLE_include_directive : require
#include "shared/constants.h"
#include "glsl/sort.h"

layout(local_size_x = SORT_GROUP) in;

shared uint digits[SORT_BINS];

void main() {
    uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint tiles = sortState[SORT_STATE_TILES];
    if (tile >= tiles) {
        return;  // the same for the whole workgroup
    }
    uint lid = gl_LocalInvocationIndex;
    if (lid < SORT_BINS) {
        digits[lid] = 0u;
    }
    barrier();
    uint n = sortState[SORT_STATE_COUNT];
    for (uint k = 0u; k < SORT_ITEMS; ++k) {
        uint i = tile * SORT_TILE + k * SORT_GROUP + lid;
        if (i < n) {
            atomicAdd(digits[sortDigit(sortKeys[push.source + i], push.shift)], 1u);
        }
    }
    barrier();
    if (lid < SORT_BINS) {
        sortHistograms[lid * tiles + tile] = digits[lid];
    }
}
