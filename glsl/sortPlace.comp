#version 460
// Deterministic grid build (STAGE_BUILD_GRID), last step (per map): the photons in sorted order, which is cell order
// with each cell's photons by id.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "glsl/dispatch.h"
#include "glsl/sort.h"
#include "shared/photon_map.h"

layout(local_size_x = GROUP_SIZE) in;

void main() {
    uint i = invocationIndex();
    if (i < sortState[SORT_STATE_COUNT]) {
        placePhoton(push.map, i, sortValues[push.source + i]);
    }
}
