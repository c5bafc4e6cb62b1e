// The CUDA kernels of one frame, behind a table of launch functions: one per stage of
// shared/stages.h, found by its STAGE_* (the grid build's steps apart). stages.cu is compiled
// as fast kernels (FMA contraction and --use_fast_math: the arithmetic GLSL drivers use) and as
// parity kernels (IEEE arithmetic and --fmad=false: photon maps and hit points that match the CPU
// backend bit for bit).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "shared/bindings.h"
#include "shared/stages.h"

namespace photon {

// Launch shapes, tunable from photon-bench.
struct LaunchConfig {
    // Photon pass 256 and tiles 8x8: the fastest of photon-bench --launch-sweep's 15 shapes on
    // the H200 (Cornell 1080p, sppm: 2.984 ms against 3.038 for 128 and 16x8; docs/performance.md).
    // The eye pass in tiles of 16x8: its fastest on the H100 (bunny 1080p 1.09 ms against 1.13,
    // 1M triangles 0.93 against 0.96), where the gather keeps 8x8.
    std::uint32_t photonBlock = 256;  // threads per block of the photon pass
    std::uint32_t eyeBlockX = 16;     // pixel tile of the eye pass (tracePixels, primary rays)
    std::uint32_t eyeBlockY = 8;
    std::uint32_t pixelBlockX = 8;    // pixel tile of the gather and the other per-pixel stages
    std::uint32_t pixelBlockY = 8;
    // Registers a thread of the sppm gather may use (ptxas's cap): 80, 64 or 128, each a kernel
    // compiled for it (the parity kernels have 80 alone). 80 on the H100: 1M triangles 0.60 ->
    // 0.52 ms, the bunny at 4K 3.12 -> 2.93, the Cornell box within 1.5% (docs/performance.md).
    std::uint32_t gatherRegisters = 80;
    std::uint32_t gridBlocks = 1056;  // blocks of the grid-stride loops over stored photons
    bool pinnedReadback = true;       // images come back through pinned memory (else pageable)
};

// Launches a stage's kernels over the frame's buffers (b.params is the frame's parameters).
using StageLaunch = void (*)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);

struct StageKernels {
    // By STAGE_*, each defined in stages.cu under its stage's name. The grid build's is null: the
    // backend runs its steps (below) around CUB's scan, whose storage it owns.
    StageLaunch stage[STAGE_COUNT];
    // The grid build's steps, each one launch over the stored photons of every map together
    // (a map is not worth a launch of its own: the global map's steps took 3–5 µs each).
    // Count: cell key of each stored photon, and photons per cell.
    void (*countCells)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);
    // Scatter: photons into cell order, from cellStart; leaves cellCounts at zero.
    void (*scatterPhotons)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);
    // Deterministic: the scatter, then each cell in photon id order (photon_map.h).
    void (*orderPhotons)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);
    // Not a stage: photon-bench's probe of the traversal alone (tracePrimaryRay), adding the
    // pixels whose ray hit something to *hits.
    void (*tracePrimaryRays)(const Bindings& b, std::uint32_t* hits, const LaunchConfig& c, cudaStream_t s);
};

extern const StageKernels kFastKernels;
extern const StageKernels kParityKernels;
// The fast kernels compiled for scenes without media (PH_SCENE_HAS_MEDIA false in device code,
// shared/medium.h): their tracing kernels keep the registers they had before media existed.
extern const StageKernels kFastNoMediaKernels;

}  // namespace photon
