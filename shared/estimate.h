// Radiance estimates from a photon map (Jensen 2001, eq. 7.6):
//     L(x, ωo) ≈ Σ_p f(x, ωo, ωp) Φp K(|x - xp|) / (π r²)
// over the photons near x that arrived from ωo's side of the surface. Four ways to pick "near":
//   cell:        the photons of x's own grid cell, over the cell's cross-section h² (the seed).
//   radius:      all photons within r, weighted by a kernel K normalised over the disc.
//   knn:         the k nearest within a maximum radius; r is the distance to the k-th (Jensen).
//   progressive: radius, with r shrinking from frame to frame (see progressive.h).
#ifndef PHOTON_SHARED_ESTIMATE_H
#define PHOTON_SHARED_ESTIMATE_H

#include "bindings.h"
#include "bsdf.h"
#include "grid.h"

PH_NAMESPACE_BEGIN

// The surface point being shaded.
struct Shading {
    vec3 position;
    vec3 normal;  // faces wo
    vec3 wo;
    Material material;
};

// Kernel profiles, unnormalised; kernelNorm makes each integrate to 1 over the disc of radius r
// once divided by πr². Cone: Jensen's filter with k = 1.
PH_FN float kernelProfile(uint kernel, float d2, float r2) {
    if (kernel == KERNEL_CONE) {
        return 1.0f - sqrt(d2 / r2);
    }
    if (kernel == KERNEL_EPANECHNIKOV) {
        return 1.0f - d2 / r2;
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

// f(ωo, ωp) for a photon arriving from ωp, or 0 if it came from behind the surface. Lambertian
// surfaces return 1 and get albedo/π once, outside the loop (estimateScale).
PH_FN vec3 photonReflectance(PH_IN(Shading) s, uint incoming) {
    vec3 wi = octDecode(incoming);
    if (s.material.type == MATERIAL_DIFFUSE) {
        return dot(wi, s.normal) > 0.0f ? vec3(1.0f) : vec3(0.0f);
    }
    return evalBsdf(s.material, s.wo, wi, s.normal);
}

PH_FN vec3 estimateScale(PH_IN(Shading) s) {
    return s.material.type == MATERIAL_DIFFUSE ? s.material.albedo * INV_PI : vec3(1.0f);
}

// Walks the cells that a ball (x, r) overlaps. Hashed grids have cells of edge 2r, so at most
// two per axis; their buckets can repeat, and a repeated bucket is skipped.
struct CellQuery {
    ivec3 lo;
    ivec3 hi;
    ivec3 cell;
    uint visitedCount;
    uint visited[QUERY_CELLS_MAX];
};

PH_FN CellQuery beginCellQuery(vec3 x, float radius, PH_IN(GridParams) grid) {
    CellQuery q;
    q.lo = cellOf(x - vec3(radius), grid);
    q.hi = cellOf(x + vec3(radius), grid);
    if (grid.kind == GRID_HASHED) {
        q.hi = min(q.hi, q.lo + ivec3(1));
    }
    q.cell = q.lo;
    q.visitedCount = 0u;
    return q;
}

PH_FN bool nextCell(PH_INOUT(CellQuery) q, PH_IN(GridParams) grid, PH_OUT(uint) key) {
    while (q.cell.z <= q.hi.z) {
        ivec3 c = q.cell;
        q.cell.x += 1;
        if (q.cell.x > q.hi.x) {
            q.cell.x = q.lo.x;
            q.cell.y += 1;
            if (q.cell.y > q.hi.y) {
                q.cell.y = q.lo.y;
                q.cell.z += 1;
            }
        }
        key = cellKey(c, grid);
        if (grid.kind == GRID_BOUNDED) {
            return true;
        }
        bool seen = false;
        for (uint i = 0u; i < q.visitedCount; ++i) {
            seen = seen || q.visited[i] == key;
        }
        if (!seen) {
            q.visited[q.visitedCount] = key;
            q.visitedCount += 1u;
            return true;
        }
    }
    return false;
}

// Photons of the map's cell `key`: sortedPhotons[photonOffset + begin .. photonOffset + end).
PH_FN void cellRange(BUF_PARAM PH_IN(GridParams) grid, uint key, PH_OUT(uint) begin, PH_OUT(uint) end) {
    begin = grid.photonOffset + BUF(cellStart)[grid.cellOffset + key];
    end = grid.photonOffset + BUF(cellStart)[grid.cellOffset + key + 1u];
}

PH_FN vec3 estimateRadius(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s, float radius, uint kernel) {
    float r2 = radius * radius;
    vec3 sum = vec3(0.0f);
    CellQuery q = beginCellQuery(s.position, radius, grid);
    uint key;
    while (nextCell(q, grid, key)) {
        uint begin;
        uint end;
        cellRange(BUF_ARG grid, key, begin, end);
        for (uint i = begin; i < end; ++i) {
            Photon p = BUF(sortedPhotons)[i];
            vec3 d = p.position - s.position;
            float d2 = dot(d, d);
            if (d2 < r2) {
                sum += photonReflectance(s, p.incoming) * p.power * kernelProfile(kernel, d2, r2);
            }
        }
    }
    return sum * estimateScale(s) * (kernelNorm(kernel) / (PI * r2));
}

// The seed's estimator: every photon of the cell holding x, spread over the cell's cross-section.
PH_FN vec3 estimateCell(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s) {
    ivec3 cell = cellOf(s.position, grid);
    uint begin;
    uint end;
    cellRange(BUF_ARG grid, cellKey(cell, grid), begin, end);
    vec3 sum = vec3(0.0f);
    for (uint i = begin; i < end; ++i) {
        Photon p = BUF(sortedPhotons)[i];
        if (grid.kind == GRID_BOUNDED || all(equal(cellOf(p.position, grid), cell))) {
            sum += photonReflectance(s, p.incoming) * p.power;
        }
    }
    return sum * estimateScale(s) / (grid.cellSize * grid.cellSize);
}

// Jensen's k-nearest-neighbour estimate with a max-heap of the k closest photons so far.
PH_FN vec3 estimateKnn(BUF_PARAM PH_IN(GridParams) grid, PH_IN(Shading) s, float maxRadius, uint k, uint kernel) {
    float heapDistance[KNN_MAX];
    uint heapPhoton[KNN_MAX];
    uint count = 0u;
    float maxR2 = maxRadius * maxRadius;
    CellQuery q = beginCellQuery(s.position, maxRadius, grid);
    uint key;
    while (nextCell(q, grid, key)) {
        uint begin;
        uint end;
        cellRange(BUF_ARG grid, key, begin, end);
        for (uint i = begin; i < end; ++i) {
            Photon p = BUF(sortedPhotons)[i];
            vec3 d = p.position - s.position;
            float d2 = dot(d, d);
            if (d2 >= maxR2 || (count == k && d2 >= heapDistance[0])) {
                continue;
            }
            if (isBlack(photonReflectance(s, p.incoming))) {
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
        Photon p = BUF(sortedPhotons)[heapPhoton[j]];
        sum += photonReflectance(s, p.incoming) * p.power * kernelProfile(kernel, heapDistance[j], r2);
    }
    return sum * estimateScale(s) * (kernelNorm(kernel) / (PI * r2));
}

// The estimate the frame's settings ask for, from photon map `map` (MAP_GLOBAL or MAP_CAUSTIC).
PH_FN vec3 photonEstimate(BUF_PARAM uint map, PH_IN(Shading) s) {
    GridParams grid = BUF(params).grids[map];
    if (grid.photonCapacity == 0u) {
        return vec3(0.0f);
    }
    uint estimator = BUF(params).estimator;
    if (estimator == ESTIMATOR_CELL) {
        return estimateCell(BUF_ARG grid, s);
    }
    if (estimator == ESTIMATOR_KNN) {
        return estimateKnn(BUF_ARG grid, s, grid.radius, BUF(params).knnK, BUF(params).kernel);
    }
    return estimateRadius(BUF_ARG grid, s, grid.radius, BUF(params).kernel);
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
