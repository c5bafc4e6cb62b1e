// The stages of a frame, declared once, in the order a frame runs them. PH_STAGES is a list that
// the C and GLSL preprocessors both expand (as PH_BUFFERS in bindings.h): into the STAGE_*
// constants, into the hosts' table of names (kStages) that every report loops over, and into each
// backend's table of stage functions, which carry the stage's name in every backend (cpu/,
// cuda/stages.cu, vulkan/record_frame.cpp). core/frame/renderer.cpp runs them in this order.
//
// A row is X(NAME, id, name, label):
//   NAME   the stage constant is STAGE_<NAME>
//   id     its number and its timer slot (StageTimes); rows are numbered 0, 1, 2, ... in order
//   name   its name in code and in reports: JSON keys and CSV columns (photon-render --stats,
//          photon-bench, photon-view --stats, tools/plot_bench.py)
//   label  photon-bench's short column heading in its printed table
//
//   tracePhotons  emit photons from the lights and follow them, appending to the two maps
//   buildGrid     sort each map's photons by grid cell (count, exclusive scan, scatter)
//   tracePixels   eye paths through mirrors and glass to hit points, with direct light
//   reproject     when the camera moved (FLAG_REPROJECT), each pixel's history taken from where
//                 its visible point was seen (reproject.h)
//   gather        photon density estimates (and final gather) at the hit points
//   accumulate    fold the frame into the running mean (and the auxiliary images, aov.h)
//   denoise       filter the running mean, guided by the auxiliary images (denoise.h); only
//                 under FLAG_DENOISE, and a frame whose image nobody looks at may skip it
#ifndef PHOTON_SHARED_STAGES_H
#define PHOTON_SHARED_STAGES_H

#include "portable.h"

#define PH_STAGES(X)                                \
    X(TRACE_PHOTONS, 0u, tracePhotons, "trace ph")  \
    X(BUILD_GRID, 1u, buildGrid, "grid")            \
    X(TRACE_PIXELS, 2u, tracePixels, "trace px")    \
    X(REPROJECT, 3u, reproject, "reproj")           \
    X(GATHER, 4u, gather, "gather")                 \
    X(ACCUMULATE, 5u, accumulate, "accum")          \
    X(DENOISE, 6u, denoise, "denoise")

PH_NAMESPACE_BEGIN

#define PH_STAGE_CONSTANT(NAME, id, name, label) PH_CONST uint STAGE_##NAME = id;
PH_STAGES(PH_STAGE_CONSTANT)
#define PH_COUNT_STAGE(NAME, id, name, label) 1u +
PH_CONST uint STAGE_COUNT = PH_STAGES(PH_COUNT_STAGE) 0u;

PH_NAMESPACE_END

#ifdef __cplusplus
namespace photon {

// One row of the list, for the hosts.
struct StageInfo {
    uint id;            // STAGE_*
    const char* name;   // as in code and reports
    const char* label;  // photon-bench's table heading
};

#define PH_STAGE_INFO(NAME, id, name, label) {id, #name, label},
// kStages[i] is stage i.
inline constexpr StageInfo kStages[] = {PH_STAGES(PH_STAGE_INFO)};
static_assert(sizeof(kStages) / sizeof(kStages[0]) == STAGE_COUNT, "one stage per row");

constexpr bool stagesNumberedInOrder() {
    for (uint i = 0; i < STAGE_COUNT; ++i) {
        if (kStages[i].id != i) {
            return false;
        }
    }
    return true;
}
static_assert(stagesNumberedInOrder(), "PH_STAGES rows must be stages 0, 1, 2, ... in order");

}  // namespace photon
#endif

#endif
