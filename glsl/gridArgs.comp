#version 460
// STAGE_BUILD_GRID, step 0: the indirect-dispatch arguments of the count and scatter passes of
// each map, so that they run over the photons the photon pass stored rather than the capacity.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_map.h"
#include "glsl/dispatch.h"

layout(local_size_x = 1) in;

void main() {
    for (uint map = 0u; map < MAP_COUNT; ++map) {
        uint groups = (storedPhotons(map) + GROUP_SIZE - 1u) / GROUP_SIZE;
        uint x = min(groups, MAX_GROUPS_X);
        uint y = x == 0u ? 0u : (groups + x - 1u) / x;
        counters[GRID_ARGS + 3u * map + 0u] = x;
        counters[GRID_ARGS + 3u * map + 1u] = y;
        counters[GRID_ARGS + 3u * map + 2u] = 1u;
    }
}
