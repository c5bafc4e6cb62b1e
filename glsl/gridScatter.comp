#version 460
// Stage buildGrid, step 3 (per map): every stored photon to a free place of its cell in
// sortedPhotons. Counting each cell's count back down hands out its places, and leaves the counts
// at zero for the next frame's count pass.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;
layout(push_constant) uniform Push { uint map; } push;

void main() {
    uint i = invocationIndex();
    if (i >= storedPhotons(push.map)) {
        return;
    }
    GridParams grid = params.grids[push.map];
    uint key = photonKeys[grid.photonOffset + i];
    uint place = cellStart[grid.cellOffset + key] + atomicAdd(cellCounts[grid.cellOffset + key], 0xffffffffu) - 1u;
    sortedPhotons[grid.photonOffset + place] = photons[grid.photonOffset + i];
}
