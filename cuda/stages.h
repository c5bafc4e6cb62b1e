// The CUDA kernels of one frame, one per stage, behind a table of launch functions. stages.cu is
// compiled three times: with FMA contraction (the fast build), without (--fmad=false, the parity
// build, whose photon maps and hit points match the CPU backend bit for bit), and with 16-byte
// photons (PH_COMPACT_PHOTONS, an experiment measured in docs/performance.md).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "shared/bindings.h"

namespace photon {

// Launch shapes, tunable from photon-bench.
struct LaunchConfig {
    std::uint32_t photonBlock = 128;  // threads per block of the photon pass
    std::uint32_t pixelBlockX = 16;   // pixel tile of the eye pass and the gather
    std::uint32_t pixelBlockY = 8;
    std::uint32_t gridBlocks = 1056;  // blocks of the grid-stride loops over stored photons
    bool compactPhotons = false;      // gather from 16-byte photons (no side test, Lambertian only)
    bool pinnedReadback = true;       // images come back through pinned memory (else pageable)
    bool radixSortGrid = false;       // buildGrid orders photons by CUB radix sort, not the scatter
};

struct StageKernels {
    // Emits and traces paths [0, paths), appending photons to both maps.
    void (*tracePhotons)(const Bindings& b, std::uint32_t paths, const LaunchConfig& c, cudaStream_t s);
    // Cell key of each stored photon of `map`, and photons per cell (cellCounts, cleared before).
    void (*countCells)(const Bindings& b, std::uint32_t map, const LaunchConfig& c, cudaStream_t s);
    // Photons of `map` into cell order, from cellStart; leaves cellCounts at zero for the next frame.
    void (*scatterPhotons)(const Bindings& b, std::uint32_t map, const LaunchConfig& c, cudaStream_t s);
    void (*tracePixels)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);
    void (*gather)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);
    void (*accumulate)(const Bindings& b, const LaunchConfig& c, cudaStream_t s);
};

extern const StageKernels kFastKernels;
extern const StageKernels kParityKernels;
extern const StageKernels kCompactKernels;

}  // namespace photon
