// The kernels of one frame. No light transport here: each kernel maps threads to photons or
// pixels and calls the shared/ function for its stage. PHOTON_KERNEL_TABLE names the table this
// compilation defines (kFastKernels or kParityKernels, see stages.h).
#include "stages.h"

#include <cooperative_groups.h>

#include "cuda_check.h"
#include "shared/eye_trace.h"
#include "shared/gather.h"
#include "shared/grid.h"
#include "shared/photon_trace.h"
#include "shared/progressive.h"

namespace photon {
namespace PHOTON_KERNEL_NAMESPACE {

namespace cg = cooperative_groups;

// The gather is bound by memory latency: more resident warps hide more of it. With blocks of up to
// 256 threads, 4 per SM leaves 64 registers a thread; final gather needs more and gets them.
constexpr int kGatherThreads = 256;
constexpr int gatherMinBlocks(uint globalMode) { return globalMode == GLOBAL_DIRECT ? 4 : 1; }

// Appends to a map. The threads of a warp that store at the same time reserve their slots with
// one atomic: a million threads on one counter would otherwise queue up at L2.
__device__ inline void appendPhoton(const Bindings& b, uint map, const Photon& p) {
    const GridParams& grid = b.params.grids[map];
    cg::coalesced_group active = cg::coalesced_threads();
    uint base = 0u;
    if (active.thread_rank() == 0) {
        base = atomicAdd(&b.counters[COUNTER_STORED_GLOBAL + map], active.size());
    }
    uint slot = active.shfl(base, 0) + active.thread_rank();
    if (slot < grid.photonCapacity) {
        b.photons[grid.photonOffset + slot] = p;
    }
}

__global__ void tracePhotonsKernel(Bindings b, uint paths) {
    uint i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= paths) {
        return;
    }
    PhotonPath path = startPhotonPath(b, i);
    while (photonPathAlive(path)) {
        Photon p;
        uint store = photonBounce(b, path, p);
        if (store & STORE_GLOBAL) {
            appendPhoton(b, MAP_GLOBAL, p);
        }
        if (store & STORE_CAUSTIC) {
            appendPhoton(b, MAP_CAUSTIC, p);
        }
    }
}

// Photons stored in `map` this frame, capped at its capacity.
__device__ inline uint storedPhotons(const Bindings& b, uint map) {
    return min(b.counters[COUNTER_STORED_GLOBAL + map], b.params.grids[map].photonCapacity);
}

__global__ void countCellsKernel(Bindings b, uint map) {
    const GridParams& grid = b.params.grids[map];
    uint n = storedPhotons(b, map);
    for (uint i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
        uint key = photonCellKey(b.photons[grid.photonOffset + i].position, grid);
        b.photonKeys[grid.photonOffset + i] = key;
        atomicAdd(&b.cellCounts[grid.cellOffset + key], 1u);
    }
}

__global__ void scatterPhotonsKernel(Bindings b, uint map) {
    const GridParams& grid = b.params.grids[map];
    uint n = storedPhotons(b, map);
    for (uint i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x) {
        uint key = b.photonKeys[grid.photonOffset + i];
        // Counting down the cell's count hands out its slots and leaves the count at zero.
        uint slot = atomicSub(&b.cellCounts[grid.cellOffset + key], 1u) - 1u;
        uint place = grid.photonOffset + b.cellStart[grid.cellOffset + key] + slot;
#ifdef PH_COMPACT_PHOTONS
        const Photon& p = b.photons[grid.photonOffset + i];
        CompactPhoton c;
        c.position = p.position;
        c.power = encodeRgbe(p.power);
        b.compactPhotons[place] = c;
#else
        b.sortedPhotons[place] = b.photons[grid.photonOffset + i];
#endif
    }
}

__device__ inline bool pixelOf(const Bindings& b, uint& pixel) {
    uint x = blockIdx.x * blockDim.x + threadIdx.x;
    uint y = blockIdx.y * blockDim.y + threadIdx.y;
    pixel = y * b.params.width + x;
    return x < b.params.width && y < b.params.height;
}

__global__ void tracePixelsKernel(Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        b.hitPoints[p] = tracePixel(b, p);
    }
}

// One kernel per estimator and global mode: constants fold away the others' code (the k-nearest
// heap, final gather), which would otherwise cost registers and stack in every variant.
template <uint Estimator, uint GlobalMode>
__global__ void __launch_bounds__(kGatherThreads, gatherMinBlocks(GlobalMode)) gatherKernel(Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        b.frameRadiance[p] = vec4(gatherPixel(b, p, Estimator, GlobalMode), 1.0f);
    }
}

__global__ void accumulateKernel(Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        b.accumulation[p] = accumulateMean(b.accumulation[p], b.frameRadiance[p], b.params.accumulated);
    }
}

dim3 pixelGrid(const Bindings& b, const LaunchConfig& c) {
    return dim3((b.params.width + c.pixelBlockX - 1) / c.pixelBlockX, (b.params.height + c.pixelBlockY - 1) / c.pixelBlockY);
}

void tracePhotons(const Bindings& b, std::uint32_t paths, const LaunchConfig& c, cudaStream_t s) {
    if (paths > 0) {
        tracePhotonsKernel<<<(paths + c.photonBlock - 1) / c.photonBlock, c.photonBlock, 0, s>>>(b, paths);
        CUDA_CHECK_LAUNCH("tracePhotons");
    }
}

void countCells(const Bindings& b, std::uint32_t map, const LaunchConfig& c, cudaStream_t s) {
    countCellsKernel<<<c.gridBlocks, 256, 0, s>>>(b, map);
    CUDA_CHECK_LAUNCH("buildGrid (count)");
}

void scatterPhotons(const Bindings& b, std::uint32_t map, const LaunchConfig& c, cudaStream_t s) {
    scatterPhotonsKernel<<<c.gridBlocks, 256, 0, s>>>(b, map);
    CUDA_CHECK_LAUNCH("buildGrid (scatter)");
}

void tracePixels(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    tracePixelsKernel<<<pixelGrid(b, c), dim3(c.pixelBlockX, c.pixelBlockY), 0, s>>>(b);
    CUDA_CHECK_LAUNCH("tracePixels");
}

template <uint Estimator>
void gatherWith(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    dim3 grid = pixelGrid(b, c);
    dim3 block(c.pixelBlockX, c.pixelBlockY);
    if (b.params.globalMode == GLOBAL_FINAL_GATHER) {
        gatherKernel<Estimator, GLOBAL_FINAL_GATHER><<<grid, block, 0, s>>>(b);
    } else {
        gatherKernel<Estimator, GLOBAL_DIRECT><<<grid, block, 0, s>>>(b);
    }
}

void gather(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    switch (b.params.estimator) {
        case ESTIMATOR_CELL:
            gatherWith<ESTIMATOR_CELL>(b, c, s);
            break;
        case ESTIMATOR_KNN:
            gatherWith<ESTIMATOR_KNN>(b, c, s);
            break;
        default:  // radius and progressive are the same estimate
            gatherWith<ESTIMATOR_RADIUS>(b, c, s);
            break;
    }
    CUDA_CHECK_LAUNCH("gather");
}

void accumulate(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    accumulateKernel<<<pixelGrid(b, c), dim3(c.pixelBlockX, c.pixelBlockY), 0, s>>>(b);
    CUDA_CHECK_LAUNCH("accumulate");
}

}  // namespace PHOTON_KERNEL_NAMESPACE

const StageKernels PHOTON_KERNEL_TABLE = {
    PHOTON_KERNEL_NAMESPACE::tracePhotons, PHOTON_KERNEL_NAMESPACE::countCells,
    PHOTON_KERNEL_NAMESPACE::scatterPhotons, PHOTON_KERNEL_NAMESPACE::tracePixels,
    PHOTON_KERNEL_NAMESPACE::gather, PHOTON_KERNEL_NAMESPACE::accumulate,
};

}  // namespace photon
