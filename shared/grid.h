// The photon map is a linear spatial hash (Wu's choice, after Gupte 2011): photons sorted by
// cell in one array, and cellStart[c] .. cellStart[c + 1] the range of cell c. No pointers, one
// allocation, one copy. Two ways to number cells:
//   GRID_BOUNDED: Wu's k³ cells over the scene's bounding cube; points outside are clamped
//                 into the border cells (her equation (1), with the clamping she describes).
//   GRID_HASHED:  unbounded integer cells (edge r or 2r) hashed into a power-of-two table
//                 (Teschner et al., "Optimized Spatial Hashing for Collision Detection", 2003).
//                 Cells are hashed in 4×4×4 blocks: Teschner's hash of the block, and the cell's
//                 place in its block as the key's low 6 bits. Any 4 consecutive cells along each
//                 axis therefore have distinct keys, so a query that spans at most 3 cells per
//                 axis never meets a bucket twice and needs no bookkeeping. Distant cells may
//                 still share a bucket: queries filter by distance.
#ifndef PHOTON_SHARED_GRID_H
#define PHOTON_SHARED_GRID_H

#include "layout.h"

PH_NAMESPACE_BEGIN

// Integer cell of a point. floor(), not a cast, so that -0.5 lands in cell -1.
PH_FN ivec3 cellOf(vec3 p, PH_IN(GridParams) grid) {
    vec3 c = floor((p - grid.origin) / grid.cellSize);
    if (grid.kind == GRID_BOUNDED) {
        c = clamp(c, vec3(0.0f), vec3(float(grid.resolution - 1u)));
    } else {
        c = clamp(c, vec3(-1.0e9f), vec3(1.0e9f));
    }
    return ivec3(c);
}

PH_FN uint teschnerHash(ivec3 c) {
    return (uint(c.x) * 73856093u) ^ (uint(c.y) * 19349663u) ^ (uint(c.z) * 83492791u);
}

// Index of a cell in the map's cell arrays. The hashed table has at least 64 entries.
PH_FN uint cellKey(ivec3 c, PH_IN(GridParams) grid) {
    if (grid.kind == GRID_BOUNDED) {
        return (uint(c.z) * grid.resolution + uint(c.y)) * grid.resolution + uint(c.x);
    }
    // Cells are within ±1e9 (cellOf), so the bias keeps them positive: then >> 2 is floor(c / 4).
    uvec3 u = uvec3(c + ivec3(0x40000000));
    uint inBlock = (u.x & 3u) | ((u.y & 3u) << 2u) | ((u.z & 3u) << 4u);
    uint block = teschnerHash(ivec3(u >> 2u));
    return ((block << 6u) | inBlock) & (grid.cellCount - 1u);
}

PH_FN uint photonCellKey(vec3 p, PH_IN(GridParams) grid) { return cellKey(cellOf(p, grid), grid); }

PH_NAMESPACE_END

#endif
