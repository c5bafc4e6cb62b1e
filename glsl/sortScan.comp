#version 460
// Deterministic grid build (STAGE_BUILD_GRID), a radix pass's second step, in one workgroup: the exclusive prefix sum
// of the digit-major tile counts, which makes each entry the first place of its (digit, tile)
// group: all keys of smaller digits, then those of the digit in earlier tiles, come before it.
#extension GL_GOOGLE_include_directive : require
#include "shared/constants.h"
#include "glsl/sort.h"

layout(local_size_x = SORT_GROUP) in;

shared uint partial[SORT_GROUP];

void main() {
    uint lid = gl_LocalInvocationIndex;
    uint total = SORT_BINS * sortState[SORT_STATE_TILES];
    uint run = (total + SORT_GROUP - 1u) / SORT_GROUP;  // consecutive entries per invocation
    uint first = lid * run;
    uint sum = 0u;
    for (uint k = 0u; k < run; ++k) {
        if (first + k < total) {
            sum += sortHistograms[first + k];
        }
    }
    partial[lid] = sum;
    barrier();
    // Hillis and Steele's inclusive scan of the invocations' sums.
    for (uint offset = 1u; offset < SORT_GROUP; offset *= 2u) {
        uint before = lid >= offset ? partial[lid - offset] : 0u;
        barrier();
        partial[lid] += before;
        barrier();
    }
    uint running = partial[lid] - sum;
    for (uint k = 0u; k < run; ++k) {
        if (first + k < total) {
            uint count = sortHistograms[first + k];
            sortHistograms[first + k] = running;
            running += count;
        }
    }
}
