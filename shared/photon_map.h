// STAGE_BUILD_GRID: the photons that the photon pass appended, sorted by grid cell into the photon
// maps (a counting sort), the same way in every backend:
//   count    one invocation per stored photon: its cell key, and photons per cell (an atomic add);
//   scan     the backend's own exclusive prefix sum of the counts into cellStart;
//   scatter  one invocation per stored photon: a free place in its cell, handed out by counting the
//            cell's count back down, which also leaves the counts at zero for the next frame; the
//            photon goes there in the maps' 16-byte form (map_photon.h).
// The scatter's places follow atomic timing, so a cell's photons may come in any order. The
// canonical order is by photon id within each cell (the order of a serial trace: path by path,
// bounce by bounce): the CPU backend builds it, and the GPU backends build it when asked to be
// deterministic, sorting (cell key, id) pairs instead of scattering. Only then does the same seed
// give the same image bit for bit, since estimates sum a cell's photons in order and subsample
// dense cells by their place in it.
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

#endif

// The deterministic build's sort key of stored photon i (after the count step): cell key and
// photon id as one (keyBits + photonIdBits)-bit number, (cell << photonIdBits) | id, in two words
// (low, high).
PH_FN uvec2 photonSortKey(BUF_PARAM uint map, uint i) {
    uint photonOffset = BUF(params).grids[map].photonOffset;
    uint cell = BUF(photonKeys)[photonOffset + i];
    uint id = BUF(photons)[photonOffset + i].id;
    uint idBits = BUF(params).photonIdBits;
    if (idBits >= 32u) {
        return uvec2(id, cell);
    }
    return uvec2(id | (cell << idBits), cell >> (32u - idBits));
}

// Bits of the sort key of map `map` (the hosts sort that many low bits).
PH_FN uint photonSortKeyBits(PH_IN(FrameParams) p, uint map) { return p.grids[map].keyBits + p.photonIdBits; }

PH_NAMESPACE_END

#endif
