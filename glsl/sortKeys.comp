#version 460
// Deterministic grid build (STAGE_BUILD_GRID), step 1 (per map, after the count step): each stored photon's
// (cell key, photon id) sort key, and its index as the value.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_map.h"
#include "glsl/dispatch.h"
#include "glsl/sort.h"

layout(local_size_x = GROUP_SIZE) in;

void main() {
    uint i = invocationIndex();
    if (i < sortState[SORT_STATE_COUNT]) {
        sortKeys[push.target + i] = photonSortKey(push.map, i);
        sortValues[push.target + i] = i;
    }
}
