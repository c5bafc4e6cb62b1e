// Radiance estimates from a photon map (Jensen 2001, eq. 7.6):
//     L(x, ωo) ≈ Σ_p f(x, ωo, ωp) Φp K(|x - xp|) / (π r²)
// over the photons near x that arrived from ωo's side of the surface. "Near" is a disc rather than
// a ball (Jensen 2001, §7.2): within r of x and within DISC_THICKNESS·r of the tangent plane, which
// keeps photons of a neighbouring wall out of a corner's estimate, still holds curved surfaces whose
// radius exceeds 2r, and lets a query visit only the cells the disc crosses. Ways to pick "near":
//   cell:        the photons of x's own grid cell, over the cell's cross-section h² (Wu's estimate).
//   radius:      all photons within r, weighted by a kernel K normalised over the disc.
//   knn:         the k nearest within a maximum radius; r is the distance to the k-th (Jensen).
//   progressive: radius, with r shrinking from frame to frame (see progressive.h).
#ifndef PHOTON_SHARED_ESTIMATE_H
#define PHOTON_SHARED_ESTIMATE_H

#include "bindings.h"
#include "bsdf.h"
#include "grid.h"
#include "map_photon.h"
#include "spectral.h"

PH_NAMESPACE_BEGIN

// The point where photons are gathered: what their reflectance needs of it. Its material is
// looked up again only where a photon needs the full BSDF (shadingMaterial, not on Lambertian
// surfaces), with the textured albedo, metallic and roughness of the point: the loops over photons
// then carry a few registers instead of a 96-byte Material (which spilled on CUDA).
struct Shading {
    vec3 position;
    vec3 normal;           // shading normal, facing wo: what the BSDF sees
    vec3 geometricNormal;  // facing wo: the side photons must come from, the plane of the disc
    vec3 wo;
    vec3 albedo;           // as the textures make it here
    vec3 specular;         // the glossy lobe's colour (at the frame's wavelengths, as albedo)
    float metallic;
    float roughness;
    uint material;         // index into materials
    bool lambertian;       // of storedPart(material): the BSDF is albedo/π
};

PH_FN Shading makeShading(vec3 position, vec3 normal, vec3 geometricNormal, vec3 wo, uint material,
                          PH_IN(Material) textured) {
    Shading s;
    s.position = position;
    s.normal = normal;
    s.geometricNormal = geometricNormal;
    s.wo = wo;
    s.albedo = textured.albedo;
    s.specular = textured.specular;
    s.metallic = textured.metallic;
    s.roughness = textured.roughness;
    s.material = material;
    s.lambertian = surfaceIs(storedPart(textured), SURFACE_LAMBERTIAN);
    return s;
}

// The part of the point's material that photons and gather rays see (storedPart), textured.
PH_FN Material shadingMaterial(BUF_PARAM PH_IN(Shading) s) {
    Material m = storedPart(BUF(materials)[s.material]);
    m.albedo = s.albedo;
    m.specular = s.specular;
    m.metallic = s.metallic;
    m.roughness = s.roughness;
    return m;
}

// Kernel profiles of d²/r², unnormalised; kernelNorm makes each integrate to 1 over the disc of
// radius r once divided by πr². Cone: Jensen's filter with k = 1.
PH_FN float kernelProfile(uint kernel, float t) {
    if (kernel == KERNEL_CONE) {
        return 1.0f - sqrt(t);
    }
    if (kernel == KERNEL_EPANECHNIKOV) {
        return 1.0f - t;
    }
    return 1.0f;
}

PH_FN float kernelNorm(uint kernel) {
    if (kernel == KERNEL_CONE) {
        return 3.0f;
    }
    if (kernel == KERNEL_EPANECHNIKOV) {
        return 2.0f;
    }
    return 1.0f;
}

PH_FN_OUTLINED vec3 photonBsdf(BUF_PARAM PH_IN(Shading) s, uint incoming) {
    return evalBsdf(shadingMaterial(BUF_ARG s), s.wo, octDecode(incoming), s.normal);
}

// f(ωo, ωp) for a photon arriving from ωp, or 0 if it came from behind the surface. Lambertian
// surfaces return 1 and get albedo/π once, outside the loop (estimateScale); they only need the
// side, so they skip normalising ωp.
PH_FN vec3 photonReflectance(BUF_PARAM PH_IN(Shading) s, uint incoming) {
    if (s.lambertian) {
        return dot(octDecodeUnnormalized(incoming), s.geometricNormal) > 0.0f ? vec3(1.0f) : vec3(0.0f);
    }
    if (!(dot(octDecodeUnnormalized(incoming), s.geometricNormal) > 0.0f)) {
        return vec3(0.0f);
    }
    return photonBsdf(BUF_ARG s, incoming);
}

PH_FN vec3 estimateScale(PH_IN(Shading) s) {
    return s.lambertian ? s.albedo * INV_PI : vec3(1.0f);
}

PH_CONST float DISC_THICKNESS = 0.25f;  // half-thickness of the estimation disc, in radii

// Half-extents of the bounding box of the disc of radius r about normal n, thickened by t.
PH_FN vec3 discExtent(vec3 n, float r, float t) {
    vec3 n2 = n * n;
    return r * sqrt(max(vec3(1.0f) - n2, vec3(0.0f))) + t * abs(n);
}

PH_FN MapPhoton loadMapPhoton(BUF_PARAM uint i) { return BUF(sortedPhotons)[i]; }

// Walks the cells that a box (x ± extent) overlaps. A query whose radius fits a hashed grid's cell
// (every estimator but sppm: cells of edge at least r) visits at most 3 cells per axis, whose
// keys are distinct (grid.h). A wider one (an sppm pixel whose radius exceeds the cells) may meet a
// bucket twice: it is `filtered`, keeping only the photons of the cell it is visiting.
struct CellQuery {
    ivec3 lo;
    ivec3 hi;
    ivec3 cell;  // the cell being visited (before the first: one to the left of lo)
    bool filtered;
};

PH_FN CellQuery beginCellQuery(vec3 x, vec3 extent, float radius, PH_IN(GridParams) grid) {
    CellQuery q;
    q.lo = cellOf(x - extent, grid);
    q.hi = cellOf(x + extent, grid);
    q.filtered = false;
    if (grid.kind == GRID_HASHED) {
        if (radius <= grid.cellSize) {
            q.hi = min(q.hi, q.lo + ivec3(2));  // rounding at a cell boundary must not add a fourth
        } else {
            q.filtered = any(greaterThan(q.hi - q.lo, ivec3(2)));
        }
    }
    q.cell = q.lo - ivec3(1, 0, 0);
    return q;
}

// Whether a photon found through the visited cell's bucket lies in that cell (always, unless the
// query is filtered).
PH_FN bool inVisitedCell(PH_IN(CellQuery) q, PH_IN(GridParams) grid, PH_IN(MapPhoton) p) {
    return !q.filtered || all(equal(cellOf(mapPhotonPosition(p, grid), grid), q.cell));
}

PH_FN bool nextCell(PH_INOUT(CellQuery) q, PH_IN(GridParams) grid, PH_OUT(uint) key) {
    q.cell.x += 1;
    if (q.cell.x > q.hi.x) {
        q.cell.x = q.lo.x;
        q.cell.y += 1;
        if (q.cell.y > q.hi.y) {
            q.cell.y = q.lo.y;
            q.cell.z += 1;
        }
    }
    if (q.cell.z > q.hi.z) {
        return false;
    }
    key = cellKey(q.cell, grid);
    return true;
}

// Photons of the map's cell `key`: sortedPhotons[photonOffset + begin .. photonOffset + end).
PH_FN void cellRange(BUF_PARAM PH_IN(GridParams) grid, uint key, PH_OUT(uint) begin, PH_OUT(uint) end) {
    begin = grid.photonOffset + BUF(cellStart)[grid.cellOffset + key];
    end = grid.photonOffset + BUF(cellStart)[grid.cellOffset + key + 1u];
}

// A cell holding more photons than the budget is subsampled: every stride-th photon from a random
// start, each weighted by stride. Each photon is then visited with probability exactly 1/stride,
// so the estimate stays unbiased; only cells far denser than a query needs (a caustic's focus)
// trade a little variance for a bounded cost. `u` is uniform in [0, 1); budget 0 visits all.
PH_FN uint subsampleStride(uint count, uint budget) {
    if (budget == 0u || count <= budget) {
        return 1u;
    }
    return (count + budget - 1u) / budget;
}

PH_FN uint subsampleStart(uint begin, uint stride, float u) { return begin + min(uint(u * float(stride)), stride - 1u); }

// Adds one photon's share to a radius query at s if it lies in the disc: its kernel-weighted
// reflected flux to sum.xyz, and 1 to sum.w. `x`: s.position relative to the grid's origin, as
// the maps keep positions. (Adding in place, not returning zero for the many photons outside:
// x + 0 is not free under IEEE rules.)
PH_FN void addRadiusContribution(BUF_PARAM PH_INOUT(vec4) sum, PH_IN(Shading) s, vec3 x, PH_IN(MapPhoton) p, float r2,
                                 float invR2, float thickness, uint kernel, bool count) {
    vec3 d = mapPhotonOffset(p) - x;
    float d2 = dot(d, d);
    if (d2 < r2 && abs(dot(d, s.geometricNormal)) <= thickness) {
        sum += vec4(photonReflectance(BUF_ARG s, mapPhotonIncoming(p)) * mapPhotonPower(p) * kernelProfile(kernel, d2 * invR2),
                    count ? 1.0f : 0.0f);
    }
}

// The photons within the disc of radius r at s: Σ f·Φp·K (xyz, before estimateScale and the
// normalisation by the disc's area) and, if `count`, how many there are (w; else 0), both weighted
// for subsampling. (Callers pass a constant `count`: the estimates that need no count keep its
// registers.)
// One flat loop over (cell, photon) pairs, in which each iteration either tests a photon or moves
// to the next cell: on SIMD hardware the threads of a warp then drift through their cells
// independently instead of waiting for each other at every cell boundary (the "if-if" loop of
// Aila & Laine, "Understanding the Efficiency of Ray Traversal on GPUs", HPG 2009).
PH_FN vec4 radiusQuery(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s, float radius, uint kernel, float u,
                       bool count) {
    float r2 = radius * radius;
    float invR2 = 1.0f / r2;
    float thickness = DISC_THICKNESS * radius;
    uint budget = BUF(params).gatherBudget;
    vec3 x = s.position - grid.origin;
    vec4 sum = vec4(0.0f);
    vec4 cellSum = vec4(0.0f);
    CellQuery q = beginCellQuery(s.position, discExtent(s.geometricNormal, radius, thickness), radius, grid);
    uint i = 0u;
    uint end = 0u;
    uint stride = 1u;
    while (true) {
        if (i >= end) {
            sum += cellSum * float(stride);
            cellSum = vec4(0.0f);
            uint key;
            if (!nextCell(q, grid, key)) {
                break;
            }
            uint begin;
            cellRange(BUF_ARG grid, key, begin, end);
            stride = subsampleStride(end - begin, budget);
            i = subsampleStart(begin, stride, u);
            continue;
        }
        MapPhoton p = loadMapPhoton(BUF_ARG i);
        if (inVisitedCell(q, grid, p)) {
            addRadiusContribution(BUF_ARG cellSum, s, x, p, r2, invR2, thickness, kernel, count);
        }
        i += stride;
    }
    return sum;
}

// The radius of the disc about x (geometric normal ng) that would hold k photons at the density of
// the photons about it, read off the grid, not the photons: those of the 3 × 3 × 3 cells about x
// (fewer at a bounded grid's border) over the area x's tangent plane cuts from their cube,
// (3h)² / max|n_i|. 0 where those cells are empty. Averaged over a few cells, the density never
// collapses into a caustic's focus as the k-th nearest photon's distance does.
PH_FN float cellDensityRadius(BUF_PARAM PH_IN(GridParams) grid, vec3 x, vec3 ng, float k) {
    vec3 edge = vec3(grid.cellSize);
    CellQuery q = beginCellQuery(x, edge, grid.cellSize, grid);
    float photons = 0.0f;
    uint key;
    while (nextCell(q, grid, key)) {
        uint begin;
        uint end;
        cellRange(BUF_ARG grid, key, begin, end);
        photons += float(end - begin);
    }
    if (photons == 0.0f) {
        return 0.0f;
    }
    vec3 n = abs(ng);
    float area = 9.0f * grid.cellSize * grid.cellSize / max(max(n.x, n.y), max(n.z, 1e-3f));
    return sqrt(k * area / (PI * photons));
}

// The radius estimate: the query over the disc's area, for the kernel.
PH_FN vec3 estimateRadius(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s, float radius, uint kernel, float u) {
    vec3 sum = vec3(radiusQuery(BUF_ARG grid, s, radius, kernel, u, false));
    float invR2 = 1.0f / (radius * radius);
    return sum * estimateScale(s) * (kernelNorm(kernel) * INV_PI * invR2);
}

// Wu's estimate: every photon of the cell holding x, spread over the cell's cross-section.
PH_FN vec3 estimateCell(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s, float u) {
    ivec3 cell = cellOf(s.position, grid);
    uint begin;
    uint end;
    cellRange(BUF_ARG grid, cellKey(cell, grid), begin, end);
    uint stride = subsampleStride(end - begin, BUF(params).gatherBudget);
    vec3 sum = vec3(0.0f);
    for (uint i = subsampleStart(begin, stride, u); i < end; i += stride) {
        MapPhoton p = loadMapPhoton(BUF_ARG i);
        if (grid.kind == GRID_BOUNDED || all(equal(cellOf(mapPhotonPosition(p, grid), grid), cell))) {
            sum += photonReflectance(BUF_ARG s, mapPhotonIncoming(p)) * mapPhotonPower(p);
        }
    }
    return sum * float(stride) * estimateScale(s) / (grid.cellSize * grid.cellSize);
}

// Jensen's k-nearest-neighbour estimate with a max-heap of the k closest photons so far, over the
// photons of the cells within the maximum radius. A cell denser than the gather budget is
// subsampled as the radius query does (every stride-th photon, each weighted by its cell's
// stride): the k nearest of the sample then stand for about k·stride photons within their
// distance, and the sum stays unbiased for that disc. Without it a maximum radius as wide as the
// scene (or one so small that every photon shares the grid's clamped border cells) made every
// query visit every photon: a 320×240 frame took 60 times as long.
PH_FN vec3 estimateKnn(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s, float maxRadius, uint k, uint kernel,
                       float u) {
    float heapDistance[KNN_MAX];
    uint heapPhoton[KNN_MAX];
    uint count = 0u;
    float maxR2 = maxRadius * maxRadius;
    vec3 x = s.position - grid.origin;  // as the maps keep positions
    float thickness = DISC_THICKNESS * maxRadius;
    CellQuery q = beginCellQuery(s.position, discExtent(s.geometricNormal, maxRadius, thickness), maxRadius, grid);
    uint budget = BUF(params).gatherBudget;
    uint key;
    while (nextCell(q, grid, key)) {
        uint begin;
        uint end;
        cellRange(BUF_ARG grid, key, begin, end);
        uint stride = subsampleStride(end - begin, budget);
        for (uint i = subsampleStart(begin, stride, u); i < end; i += stride) {
            MapPhoton p = loadMapPhoton(BUF_ARG i);
            vec3 d = mapPhotonOffset(p) - x;
            float d2 = dot(d, d);
            if (d2 >= maxR2 || (count == k && d2 >= heapDistance[0]) || abs(dot(d, s.geometricNormal)) > thickness) {
                continue;
            }
            if (isBlack(photonReflectance(BUF_ARG s, mapPhotonIncoming(p)))) {
                continue;
            }
            uint slot;
            if (count < k) {
                // Sift up from the new leaf.
                slot = count;
                count += 1u;
                while (slot > 0u && heapDistance[(slot - 1u) / 2u] < d2) {
                    heapDistance[slot] = heapDistance[(slot - 1u) / 2u];
                    heapPhoton[slot] = heapPhoton[(slot - 1u) / 2u];
                    slot = (slot - 1u) / 2u;
                }
            } else {
                // Replace the farthest (the root) and sift down.
                slot = 0u;
                while (true) {
                    uint child = 2u * slot + 1u;
                    if (child >= count) {
                        break;
                    }
                    if (child + 1u < count && heapDistance[child + 1u] > heapDistance[child]) {
                        child += 1u;
                    }
                    if (heapDistance[child] <= d2) {
                        break;
                    }
                    heapDistance[slot] = heapDistance[child];
                    heapPhoton[slot] = heapPhoton[child];
                    slot = child;
                }
            }
            heapDistance[slot] = d2;
            heapPhoton[slot] = i;
        }
    }
    if (count == 0u) {
        return vec3(0.0f);
    }
    float r2 = count == k ? heapDistance[0] : maxR2;
    vec3 sum = vec3(0.0f);
    for (uint j = 0u; j < count; ++j) {
        MapPhoton p = loadMapPhoton(BUF_ARG heapPhoton[j]);
        // The stride of the photon's cell, as the search above found it (its cell's bucket).
        uint begin;
        uint end;
        cellRange(BUF_ARG grid, photonCellKey(mapPhotonPosition(p, grid), grid), begin, end);
        float weight = float(subsampleStride(end - begin, budget));
        sum += photonReflectance(BUF_ARG s, mapPhotonIncoming(p)) * mapPhotonPower(p) *
               (weight * kernelProfile(kernel, heapDistance[j] / r2));
    }
    return sum * estimateScale(s) * (kernelNorm(kernel) / (PI * r2));
}

// The estimate from photon map `map` (MAP_GLOBAL or MAP_CAUSTIC) with the given ESTIMATOR_*.
// GPU backends pass a compile-time constant, so that each variant carries only its own code.
// `u` ∈ [0, 1) places the subsampling of dense cells.
PH_FN vec3 photonEstimate(BUF_PARAM uint map, PH_IN(Shading) s, uint estimator, float u) {
    GridParams grid = BUF(params).grids[map];
    if (grid.photonCapacity == 0u) {
        return vec3(0.0f);
    }
    if (estimator == ESTIMATOR_CELL) {
        return estimateCell(BUF_ARG grid, s, u);
    }
    if (estimator == ESTIMATOR_KNN) {
        return estimateKnn(BUF_ARG grid, s, grid.radius, BUF(params).knnK, BUF(params).kernel, u);
    }
    if (estimator == ESTIMATOR_RADIUS || estimator == ESTIMATOR_PROGRESSIVE) {
        return estimateRadius(BUF_ARG grid, s, grid.radius, BUF(params).kernel, u);
    }
    return vec3(uintBitsToFloat(0x7fc00000u));  // unreachable: the host dispatches known estimators only
}

// Photons in the cell holding x, for the grid-occupancy view.
PH_FN uint cellOccupancy(BUF_PARAM uint map, vec3 x) {
    GridParams grid = BUF(params).grids[map];
    uint begin;
    uint end;
    cellRange(BUF_ARG grid, photonCellKey(x, grid), begin, end);
    return end - begin;
}

PH_NAMESPACE_END

#endif
