#version 460
// Stage gather: the photon estimates at the pixels' hit points. The estimator, the global mode and
// sppm's start are specialization constants, so each pipeline variant carries only its own code
// (the k-nearest heap alone would otherwise burden every variant). Other estimators than sppm take
// one invocation per pixel; sppm's may run as a pool (shared/sppm.h, SppmGather): a workgroup
// gathers POOL_TILES tiles (a strip of them, in row-major order), its invocations taking the
// strip's pixels one at a time from a counter in shared memory as their last one ends, so that one
// whose pixels find few photons goes on to the next instead of idling until its subgroup's slowest
// is done. A subgroup steps its invocations' queries until half of them have ended one, and only
// then do those end their map or pixel and start the next, together: a query's step is a photon
// test of a few instructions, its ends and starts hundreds, which would otherwise run for one
// invocation at a time (Aila & Laine 2009's persistent threads fetch new rays so).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require
#define PH_PHOTON_MAPS_READONLY
#define PH_HIT_POINTS_READONLY
#include "shared/bindings.h"
#include "shared/sppm.h"
#include "glsl/dispatch.h"

layout(local_size_x = PIXEL_TILE_X, local_size_y = PIXEL_TILE_Y) in;
layout(constant_id = 1) const uint ESTIMATOR = 1u;    // ESTIMATOR_*
layout(constant_id = 2) const uint GLOBAL_MODE = 0u;  // GLOBAL_*
layout(constant_id = 3) const bool SPPM_START = false;  // sppmStarts
layout(constant_id = 4) const uint POOL_TILES = 0u;     // sppm: tiles a workgroup; 0: no pool

shared uint taken;

void gatherSppmPool() {
    if (gl_LocalInvocationIndex == 0u) {
        taken = 0u;
    }
    barrier();
    const uint tilePixels = PIXEL_TILE_X * PIXEL_TILE_Y;
    uint tilesX = (params.width + PIXEL_TILE_X - 1u) / PIXEL_TILE_X;
    uint tileCount = tilesX * ((params.height + PIXEL_TILE_Y - 1u) / PIXEL_TILE_Y);
    uint first = workgroupIndex() * POOL_TILES;
    SppmGather g;
    bool busy = false;
    while (true) {
        if (!busy) {
            uint w = atomicAdd(taken, 1u);
            if (w >= POOL_TILES * tilePixels) {
                return;
            }
            uint t = first + w / tilePixels;
            uint k = w % tilePixels;
            uint x = (t % tilesX) * PIXEL_TILE_X + k % PIXEL_TILE_X;
            uint y = (t / tilesX) * PIXEL_TILE_Y + k / PIXEL_TILE_X;
            if (t >= tileCount || x >= params.width || y >= params.height) {
                continue;
            }
            uint pixel = y * params.width + x;
            if (params.view == VIEW_GRID) {
                frameRadiance[pixel] = gatherStage(pixel, ESTIMATOR_SPPM, GLOBAL_DIRECT, SPPM_START);
                continue;
            }
            g = sppmGatherBegin(pixel, SPPM_START);
            busy = true;
        }
        if (g.map < SURFACE_MAP_COUNT) {
            GridParams grid = params.grids[g.map];
            RadiusQuery query = g.query;
            bool ended = false;
            while (true) {
                if (!ended) {
                    ended = !radiusQueryStep(query, grid, g.s, g.x, g.radius, KERNEL_BOX, g.u, true);
                }
                if (2u * subgroupBallotBitCount(subgroupBallot(ended)) >= subgroupBallotBitCount(subgroupBallot(true))) {
                    break;
                }
            }
            g.query = query;
            if (!ended) {
                continue;
            }
            sppmEndMap(g, SPPM_START);
        }
        if (g.map >= SURFACE_MAP_COUNT) {
            frameRadiance[g.pixel] = sppmGatherResult(g);
            busy = false;
        }
    }
}

void main() {
    if (ESTIMATOR == ESTIMATOR_SPPM && POOL_TILES > 0u) {
        gatherSppmPool();
        return;
    }
    uint pixel;
    if (!pixelOfInvocation(pixel)) {
        return;
    }
    frameRadiance[pixel] = gatherStage(pixel, ESTIMATOR, GLOBAL_MODE, SPPM_START);
}
