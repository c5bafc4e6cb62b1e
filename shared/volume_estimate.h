// The beam radiance estimate (Jarosz, Zwicker & Jensen, "The Beam Radiance Estimate for
// Volumetric Photon Mapping", EG 2008): the light a medium scatters towards the eye along a whole
// camera ray, from the volume photons within r of the ray, in one query instead of point queries
// marched along it:
//
//     L_m(o, −d) ≈ Σ_p p(θ_p) Φ_p T(t_p) K(d_p) / (π r²)
//
// t_p the photon's place along the ray, d_p its distance from the ray, T the transmittance from
// the ray's entry into the medium to t_p, p Henyey–Greenstein's phase function of the angle
// between the photon's travel and −d. The volume map stores σs·L as flux per volume (a photon at
// each scattering, medium.h), so σs cancels and the 3D kernel integrated along the ray is the 2D
// one across it.
//
// The cells within reach are found by walking the cells the ray crosses (Amanatides & Woo's 3D
// DDA): cells are at least r wide, so a photon within r of the ray lies within one cell of a
// walked cell. The first walked cell brings its 3 × 3 × 3 block, each step the 3 × 3 slab that the
// step adds to the block (the walk is monotone along every axis, so no other cell is new), and
// each photon counts in its own cell only (distant cells may share a hashed bucket): every photon
// is tested once.
#ifndef PHOTON_SHARED_VOLUME_ESTIMATE_H
#define PHOTON_SHARED_VOLUME_ESTIMATE_H

#include "estimate.h"
#include "medium.h"

PH_NAMESPACE_BEGIN

PH_CONST uint BEAM_CELLS_MAX = 27u + 9u * 4096u;  // cells a ray may visit: 4096 steps (a bound for absurd radii)

// The photons of cell c within r of the ray o' + t·d, t ∈ [tStart, tEnd) (o' relative to the
// grid's origin, as the maps keep positions). In a heterogeneous medium the density integral D
// to a photon's t is taken along the line through `anchor` = (t, D(t), dD/dt): exact where the walk
// has been, the mean density of the walked cell between (within a cell of the photon).
PH_FN vec3 beamCell(BUF_PARAM PH_IN(GridParams) grid, ivec3 c, vec3 o, vec3 d, vec2 span, PH_IN(Medium) md,
                    vec3 anchor, uint kernel) {
    vec3 sum = vec3(0.0f);
    if (grid.kind == GRID_BOUNDED) {
        int last = int(grid.resolution) - 1;
        if (any(lessThan(c, ivec3(0))) || any(greaterThan(c, ivec3(last)))) {
            return sum;  // beyond the grid: its photons are clamped into the border cells
        }
    }
    float r2 = grid.radius * grid.radius;
    vec3 sigmaT = extinctionOf(md);
    uint begin;
    uint end;
    cellRange(BUF_ARG grid, cellKey(c, grid), begin, end);
    for (uint i = begin; i < end; ++i) {
        MapPhoton p = loadMapPhoton(BUF_ARG i);
        vec3 x = mapPhotonOffset(p);
        float t = dot(x - o, d);
        if (t < span.x || t >= span.y) {
            continue;
        }
        vec3 across = o + d * t - x;
        float d2 = dot(across, across);
        if (d2 >= r2 || any(notEqual(cellOf(mapPhotonPosition(p, grid), grid), c))) {
            continue;
        }
        float phase = henyeyGreenstein(dot(octDecode(mapPhotonIncoming(p)), d), md.g);
        float depth = md.grid == NONE ? t - span.x : max(anchor.y + anchor.z * (t - anchor.x), 0.0f);
        vec3 transmittance = expNegative3(sigmaT * depth);
        PH_PRECISE vec3 contribution = mapPhotonPower(p) * transmittance * (phase * kernelProfile(kernel, d2 / r2));
        sum += contribution;
    }
    return sum;
}

// L_m along o + t·d over span (tStart, tEnd) inside medium md, from the volume map.
PH_FN vec3 beamRadianceEstimate(BUF_PARAM PH_IN(Medium) md, vec3 origin, vec3 d, vec2 span) {
    GridParams grid = BUF(params).grids[MAP_VOLUME];
    if (grid.photonCapacity == 0u || !(span.x < span.y)) {
        return vec3(0.0f);
    }
    grid.radius = min(grid.radius, grid.cellSize);  // a bounded grid's cells may be smaller
    uint kernel = BUF(params).kernel;
    vec3 o = origin - grid.origin;
    // The walk runs from the span's start, or a bounded grid's cube if the span starts outside it.
    float tWalk = span.x;
    float tEnd = span.y;
    if (grid.kind == GRID_BOUNDED) {
        Medium cube = md;
        cube.lower = vec3(0.0f);
        cube.upper = vec3(float(grid.resolution) * grid.cellSize);
        vec2 inside = mediumSpan(cube, o, d, tEnd);
        tWalk = max(tWalk, inside.x);
        tEnd = inside.y;
        if (!(tWalk < tEnd)) {
            return vec3(0.0f);
        }
    }
    // The walked cell, and for each axis the t of its next boundary and the t between boundaries.
    float h = grid.cellSize;
    vec3 p = o + d * tWalk;
    ivec3 cell = ivec3(floor(p / h));
    ivec3 step = ivec3(d.x >= 0.0f ? 1 : -1, d.y >= 0.0f ? 1 : -1, d.z >= 0.0f ? 1 : -1);
    vec3 inverse = vec3(1.0f) / abs(d);
    vec3 boundary = (vec3(cell) + max(vec3(step), vec3(0.0f))) * h;
    vec3 tNext = vec3(tWalk) + abs(boundary - p) * inverse;
    vec3 tDelta = h * inverse;
    // One flat loop over the cells to visit (the first block's 27, then each step's slab of 9),
    // so that the cell's photon loop is compiled once, not unrolled per cell.
    vec3 sum = vec3(0.0f);
    uint axis = 2u;
    int ahead = 0;
    uint group = 27u;  // cells of the current block or slab
    uint visited = 0u; // of them
    vec3 anchor = vec3(span.x, 0.0f, 0.0f);  // (t, D(t), dD/dt) where the walk has summed D to
    for (uint s = 0u; s < BEAM_CELLS_MAX; ++s) {
        if (visited == group) {
            if (min(min(tNext.x, tNext.y), tNext.z) >= tEnd) {
                break;
            }
            axis = tNext.x <= tNext.y && tNext.x <= tNext.z ? 0u : tNext.y <= tNext.z ? 1u : 2u;
            if (axis == 0u) {
                cell.x += step.x;
                tNext.x += tDelta.x;
                ahead = step.x;
            } else if (axis == 1u) {
                cell.y += step.y;
                tNext.y += tDelta.y;
                ahead = step.y;
            } else {
                cell.z += step.z;
                tNext.z += tDelta.z;
                ahead = step.z;
            }
            group = 9u;
            visited = 0u;
        }
        if (md.grid != NONE && visited == 0u) {
            // D on to the walked cell's exit: one walk over the voxels a step, none per photon.
            float reach = min(min(min(tNext.x, tNext.y), tNext.z), span.y);
            float gained = densityIntegral(BUF_ARG md, origin, d, anchor.x, reach);
            float along = reach - anchor.x;
            anchor = vec3(reach, anchor.y + gained, along > 0.0f ? gained / along : 0.0f);
        }
        int i = int(visited % 3u) - 1;
        int j = int((visited / 3u) % 3u) - 1;
        int k = group == 27u ? int(visited / 9u) - 1 : ahead;
        ivec3 n = axis == 0u ? ivec3(k, i, j) : axis == 1u ? ivec3(i, k, j) : ivec3(i, j, k);
        sum += beamCell(BUF_ARG grid, cell + n, o, d, span, md, anchor, kernel);
        visited += 1u;
    }
    float r = grid.radius;
    PH_PRECISE vec3 estimate = sum * (kernelNorm(kernel) / (PI * r * r));
    return estimate;
}

PH_NAMESPACE_END

#endif
