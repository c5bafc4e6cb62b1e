#version 460
// Deterministic grid build (STAGE_BUILD_GRID), a radix pass's third step: every key of a tile (with its value) to its
// place, stably. The tile is moved in chunks of one key per invocation, in order; within a chunk
// each key's rank among the earlier keys of its digit comes from subgroup scans of one-hot digit
// counts (four 8-bit counters to a word, so that one uvec4 scan counts all 16 digits), and the
// subgroups' totals are summed in order by one invocation per digit.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "shared/constants.h"
#include "glsl/sort.h"

// The host creates the pipeline with full subgroups required.
layout(local_size_x = SORT_GROUP) in;

shared uint subgroupPlaces[SORT_GROUP][SORT_BINS];  // per subgroup and digit: a count, then a first place
shared uint next[SORT_BINS];                        // per digit: the place of its next key

uint packedCount(uvec4 counts, uint digit) { return (counts[digit >> 2u] >> ((digit & 3u) * 8u)) & 255u; }

void main() {
    uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    uint tiles = sortState[SORT_STATE_TILES];
    if (tile >= tiles) {
        return;  // the same for the whole workgroup
    }
    uint lid = gl_LocalInvocationIndex;
    // Invocations in subgroup order, so that each subgroup owns consecutive keys of a chunk.
    uint thread = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
    if (lid < SORT_BINS) {
        next[lid] = sortHistograms[lid * tiles + tile];
    }
    barrier();
    uint n = sortState[SORT_STATE_COUNT];
    for (uint chunk = 0u; chunk < SORT_ITEMS; ++chunk) {
        uint i = tile * SORT_TILE + chunk * SORT_GROUP + thread;
        bool valid = i < n;
        uvec2 key = valid ? sortKeys[push.source + i] : uvec2(0u);
        uint value = valid ? sortValues[push.source + i] : 0u;
        uint digit = sortDigit(key, push.shift);
        uvec4 oneHot = uvec4(0u);
        if (valid) {
            oneHot[digit >> 2u] = 1u << ((digit & 3u) * 8u);
        }
        uvec4 before = subgroupExclusiveAdd(oneHot);
        uvec4 total = subgroupAdd(oneHot);
        if (gl_SubgroupInvocationID == 0u) {
            for (uint d = 0u; d < SORT_BINS; ++d) {
                subgroupPlaces[gl_SubgroupID][d] = packedCount(total, d);
            }
        }
        barrier();
        if (lid < SORT_BINS) {
            uint place = next[lid];
            for (uint s = 0u; s < gl_NumSubgroups; ++s) {
                uint count = subgroupPlaces[s][lid];
                subgroupPlaces[s][lid] = place;
                place += count;
            }
            next[lid] = place;
        }
        barrier();
        if (valid) {
            uint place = subgroupPlaces[gl_SubgroupID][digit] + packedCount(before, digit);
            sortKeys[push.target + place] = key;
            sortValues[push.target + place] = value;
        }
        barrier();  // the chunk's places are read before the next chunk's counts overwrite them
    }
}
