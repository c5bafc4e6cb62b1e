// STAGE_BUILD_GRID: the photons that the photon pass appended, sorted by grid cell into the photon
// maps (a counting sort), the same way in every backend:
//   count    one invocation per stored photon: its cell key, and photons per cell (an atomic add);
//   scan     the backend's own exclusive prefix sum of the counts into cellStart;
//   scatter  one invocation per stored photon: a free place in its cell, handed out by counting the
//            cell's count back down, which also leaves the counts at zero for the next frame; the
//            photon goes there in the maps' 16-byte form (map_photon.h).
// The scatter's places follow atomic timing, so a cell's photons may come in any order. The
// canonical order is by photon id within each cell (the order of a serial trace: path by path,
// bounce by bounce). Only in it does the same seed give the same image bit for bit, since estimates
// sum a cell's photons in order and subsample dense cells by their place in it. The deterministic
// build gets there in two more steps instead of a sort of the whole map, because cells are small
// (about 8 photons on average in the shipped scenes):
//   scatter  as above, but the place gets the photon's id and stored index in photonOrder;
//   rank     one invocation per place: the photon's rank among the ids of its chunk (ORDER_CHUNK
//            consecutive places of its cell) by counting the smaller ones; a cell of one chunk
//            is then in order, and its photon goes to its place in the map;
//   merge    one invocation per place of the larger cells: the rank within the chunk plus a
//            binary search in each other chunk of the cell (already in order) gives the rank in
//            the cell. So a cell of n photons costs n·ORDER_CHUNK + n²/ORDER_CHUNK·log ORDER_CHUNK
//            loads, not n². Of chunks of 64 to 1024 places, 128 measured fastest on the caustic
//            scene's focus (docs/performance.md); ids apart from indices halve the loads.
#ifndef PHOTON_SHARED_PHOTON_MAP_H
#define PHOTON_SHARED_PHOTON_MAP_H

#include "bindings.h"
#include "grid.h"
#include "map_photon.h"

PH_NAMESPACE_BEGIN

// Photons map `map` holds this frame: those the photon pass counted, up to the map's capacity.
PH_FN uint storedPhotons(BUF_PARAM uint map) {
    return min(BUF(counters)[COUNTER_STORED + map], BUF(params).grids[map].photonCapacity);
}

// Photon p of this frame as map `map` keeps it (map_photon.h).
PH_FN MapPhoton mapPhoton(BUF_PARAM uint map, PH_IN(Photon) p) {
    return encodeMapPhoton(p, BUF(params).grids[map], BUF(params).frameIndex, BUF(params).seed);
}

#ifndef PH_PHOTON_MAPS_READONLY  // shaders that only read the maps declare them read-only

// Count step, for stored photon i of map `map`.
PH_FN void countPhotonCell(BUF_PARAM uint map, uint i) {
    uint photonOffset = BUF(params).grids[map].photonOffset;
    uint key = photonCellKey(mapPosition(BUF(photons)[photonOffset + i].position, BUF(params).grids[map]),
                             BUF(params).grids[map]);
    BUF(photonKeys)[photonOffset + i] = key;
    PH_ATOMIC_ADD(BUF(cellCounts)[BUF(params).grids[map].cellOffset + key], 1u);
}

// Stored photon i of map `map`, in the map's form, at `place` of the map.
PH_FN void placePhoton(BUF_PARAM uint map, uint place, uint i) {
    uint photonOffset = BUF(params).grids[map].photonOffset;
    BUF(sortedPhotons)[photonOffset + place] = mapPhoton(BUF_ARG map, BUF(photons)[photonOffset + i]);
}

// A free place in the cell of stored photon i of map `map` (after the scan).
PH_FN uint cellPlace(BUF_PARAM uint map, uint i) {
    uint cell = BUF(params).grids[map].cellOffset + BUF(photonKeys)[BUF(params).grids[map].photonOffset + i];
    return BUF(cellStart)[cell] + PH_ATOMIC_ADD(BUF(cellCounts)[cell], 0xffffffffu) - 1u;
}

// Scatter step, for stored photon i of map `map`.
PH_FN void scatterPhoton(BUF_PARAM uint map, uint i) { placePhoton(BUF_ARG map, cellPlace(BUF_ARG map, i), i); }

// The deterministic build. photonOrder holds four arrays, each laid out as the photon arrays are:
// at the scatter's places the photon ids and their stored indices, then the same with each chunk
// in id order. Ids apart from indices halve what the rank loop and the binary searches read.
PH_CONST uint ORDER_CHUNK = 128u;          // places a rank step counts over (a power of two)
PH_CONST uint ORDER_IDS = 0u;
PH_CONST uint ORDER_INDICES = 1u;
PH_CONST uint ORDER_CHUNK_IDS = 2u;
PH_CONST uint ORDER_CHUNK_INDICES = 3u;
PH_CONST uint ORDER_ARRAYS = 4u;
PH_CONST uint ORDER_PLACED = 0xffffffffu;  // a chunk index whose photon the rank step placed

// Where array `array` of photonOrder holds map `map`'s places.
PH_FN uint orderOffset(BUF_PARAM uint map, uint array) {
    uint perArray = BUF(params).grids[MAP_COUNT - 1u].photonOffset + BUF(params).grids[MAP_COUNT - 1u].photonCapacity;
    return array * perArray + BUF(params).grids[map].photonOffset;
}

// The places [begin, end) of the cell of stored photon i of map `map`.
PH_FN uvec2 photonCellPlaces(BUF_PARAM uint map, uint i) {
    uint cell = BUF(params).grids[map].cellOffset + BUF(photonKeys)[BUF(params).grids[map].photonOffset + i];
    return uvec2(BUF(cellStart)[cell], BUF(cellStart)[cell + 1u]);
}

// The first place of the chunk of `place` in the cell `cell` ([begin, end)).
PH_FN uint orderChunkBegin(uvec2 cell, uint place) { return cell.x + ((place - cell.x) & ~(ORDER_CHUNK - 1u)); }

// Scatter step of the deterministic build, for stored photon i of map `map`.
PH_FN void scatterPhotonId(BUF_PARAM uint map, uint i) {
    uint place = cellPlace(BUF_ARG map, i);
    BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_IDS) + place] = BUF(photons)[BUF(params).grids[map].photonOffset + i].id;
    BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_INDICES) + place] = i;
}

// Rank step, for place `place` of map `map`.
PH_FN void rankInChunk(BUF_PARAM uint map, uint place) {
    uint ids = orderOffset(BUF_ARG map, ORDER_IDS);
    uint id = BUF(photonOrder)[ids + place];
    uint i = BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_INDICES) + place];
    uvec2 cell = photonCellPlaces(BUF_ARG map, i);
    uint begin = orderChunkBegin(cell, place);
    uint end = min(begin + ORDER_CHUNK, cell.y);
    uint rank = 0u;
    for (uint q = begin; q < end; ++q) {
        rank += BUF(photonOrder)[ids + q] < id ? 1u : 0u;
    }
    uint ordered = begin + rank;
    if (cell.y - cell.x <= ORDER_CHUNK) {
        placePhoton(BUF_ARG map, ordered, i);
        BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_CHUNK_INDICES) + ordered] = ORDER_PLACED;
    } else {
        BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_CHUNK_IDS) + ordered] = id;
        BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_CHUNK_INDICES) + ordered] = i;
    }
}

// Ids of the ordered chunk [begin, end) (at `ids` in photonOrder) below `id`.
PH_FN uint countBelow(BUF_PARAM uint ids, uint begin, uint end, uint id) {
    uint lo = begin;
    uint hi = end;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1u;
        if (BUF(photonOrder)[ids + mid] < id) {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return lo - begin;
}

// Merge step, for place `place` of map `map` (after every rank step of the map).
PH_FN void mergeChunks(BUF_PARAM uint map, uint place) {
    uint i = BUF(photonOrder)[orderOffset(BUF_ARG map, ORDER_CHUNK_INDICES) + place];
    if (i == ORDER_PLACED) {
        return;
    }
    uint ids = orderOffset(BUF_ARG map, ORDER_CHUNK_IDS);
    uint id = BUF(photonOrder)[ids + place];
    uvec2 cell = photonCellPlaces(BUF_ARG map, i);
    uint own = orderChunkBegin(cell, place);
    uint rank = place - own;
    for (uint begin = cell.x; begin < cell.y; begin += ORDER_CHUNK) {
        if (begin != own) {
            rank += countBelow(BUF_ARG ids, begin, min(begin + ORDER_CHUNK, cell.y), id);
        }
    }
    placePhoton(BUF_ARG map, cell.x + rank, i);
}

#endif

PH_NAMESPACE_END

#endif
