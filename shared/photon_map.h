// STAGE_BUILD_GRID: the photons that the photon pass appended, sorted by grid cell into the photon
// maps (a counting sort), the same way in every backend:
//   count    one invocation per stored photon: its cell key, and photons per cell (an atomic add);
//   scan     the backend's own exclusive prefix sum of the counts into cellStart;
//   scatter  one invocation per stored photon: a free place in its cell, handed out by counting the
//            cell's count back down, which also leaves the counts at zero for the next frame.
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

PH_NAMESPACE_BEGIN

// Photons map `map` holds this frame: those the photon pass counted, up to the map's capacity.
PH_FN uint storedPhotons(BUF_PARAM uint map) {
    return min(BUF(counters)[COUNTER_STORED + map], BUF(params).grids[map].photonCapacity);
}

#ifndef PH_PHOTON_MAPS_READONLY  // shaders that only read the maps declare them read-only

// Count step, for stored photon i of map `map`.
PH_FN void countPhotonCell(BUF_PARAM uint map, uint i) {
    uint photonOffset = BUF(params).grids[map].photonOffset;
    uint key = photonCellKey(BUF(photons)[photonOffset + i].position, BUF(params).grids[map]);
    BUF(photonKeys)[photonOffset + i] = key;
    PH_ATOMIC_ADD(BUF(cellCounts)[BUF(params).grids[map].cellOffset + key], 1u);
}

// Scatter step, for stored photon i of map `map` (after the scan).
PH_FN void scatterPhoton(BUF_PARAM uint map, uint i) {
    uint photonOffset = BUF(params).grids[map].photonOffset;
    uint cell = BUF(params).grids[map].cellOffset + BUF(photonKeys)[photonOffset + i];
    uint place = BUF(cellStart)[cell] + PH_ATOMIC_ADD(BUF(cellCounts)[cell], 0xffffffffu) - 1u;
    BUF(sortedPhotons)[photonOffset + place] = BUF(photons)[photonOffset + i];
}

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
