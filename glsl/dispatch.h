// How the Vulkan backend lays out its dispatches, for the host (vulkan/) and the shaders alike,
// in the dialect of shared/portable.h.
#ifndef PHOTON_GLSL_DISPATCH_H
#define PHOTON_GLSL_DISPATCH_H

#include "shared/constants.h"

PH_NAMESPACE_BEGIN

PH_CONST uint GROUP_SIZE = 64u;       // invocations per workgroup of the per-photon stages
// The per-pixel stages run in tiles of PIXEL_TILE_X × 8 pixels, so that the pixels of a subgroup
// lie close, and so do their cells. The width is a build option (PHOTON_VULKAN_PIXEL_TILE_X).
#ifndef PHOTON_PIXEL_TILE_X
#define PHOTON_PIXEL_TILE_X 8
#endif
PH_CONST uint PIXEL_TILE_X = uint(PHOTON_PIXEL_TILE_X);
PH_CONST uint PIXEL_TILE_Y = 8u;
// The eye pass's tiles, EYE_TILE_X × PIXEL_TILE_Y (build option PHOTON_VULKAN_EYE_TILE_X).
#ifndef PHOTON_EYE_TILE_X
#define PHOTON_EYE_TILE_X 16
#endif
PH_CONST uint EYE_TILE_X = uint(PHOTON_EYE_TILE_X);
PH_CONST uint MAX_GROUPS_X = 65535u;  // the smallest maxComputeWorkGroupCount[0] Vulkan allows;
                                      // larger dispatches wrap into y
// Invocations of the photon pass's pool (shared/photon_trace.h, tracePhotonPool), fewer for fewer
// paths: at least as many as the largest GPUs hold at once (an H100's 132 multiprocessors × 2048),
// since Vulkan does not say how many that is; groups beyond them start once the paths are taken,
// and end at once.
PH_CONST uint PHOTON_POOL = 1u << 19;
PH_CONST uint SCAN_ITEMS = 4u;        // cells each invocation of the scan sums in sequence

// The counters buffer: the COUNTER_* slots, then the indirect-dispatch arguments (x, y, z
// groups) of the count and scatter passes of each map, written by gridArgs.comp.
PH_CONST uint GRID_ARGS = COUNTER_COUNT;
PH_CONST uint COUNTER_WORDS = GRID_ARGS + 3u * MAP_COUNT;

PH_NAMESPACE_END

#ifndef __cplusplus
// Linear index of this workgroup in a dispatch that may wrap into y.
uint workgroupIndex() { return gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x; }

// Linear index of this invocation, in workgroups of GROUP_SIZE. (Not gl_WorkGroupSize: this file
// comes before the shader's local_size declaration, and glslang silently reads 1 there.)
uint invocationIndex() { return workgroupIndex() * GROUP_SIZE + gl_LocalInvocationID.x; }

// This invocation's pixel in a dispatch of PIXEL_TILE_X × PIXEL_TILE_Y tiles over the image; false
// for invocations of the border tiles that fall outside it.
bool pixelOfInvocation(out uint pixel) {
    uvec2 p = gl_GlobalInvocationID.xy;
    pixel = p.y * params.width + p.x;
    return p.x < params.width && p.y < params.height;
}

#endif

#endif
