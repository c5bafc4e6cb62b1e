#version 460
// Deterministic grid build (STAGE_BUILD_GRID), step 0 (per map): how many photons to sort, and the indirect-dispatch
// groups of the per-element and per-tile passes.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_map.h"
#include "glsl/dispatch.h"
#include "glsl/sort.h"

layout(local_size_x = 1) in;

void writeGroups(uint first, uint groups) {
    uint x = min(groups, MAX_GROUPS_X);
    sortState[first] = x;
    sortState[first + 1u] = x == 0u ? 0u : (groups + x - 1u) / x;
    sortState[first + 2u] = 1u;
}

void main() {
    uint n = storedPhotons(push.map);
    uint tiles = (n + SORT_TILE - 1u) / SORT_TILE;
    sortState[SORT_STATE_COUNT] = n;
    sortState[SORT_STATE_TILES] = tiles;
    writeGroups(SORT_STATE_ELEMENT_ARGS, (n + GROUP_SIZE - 1u) / GROUP_SIZE);
    writeGroups(SORT_STATE_TILE_ARGS, tiles);
}
