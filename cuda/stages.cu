// The kernels of one frame. No light transport here: each kernel maps threads to photons or
// pixels and calls the shared/ function for its stage. PHOTON_KERNEL_TABLE names the table this
// compilation defines (kFastKernels, kParityKernels or kFastNoMediaKernels, see stages.h).
// The no-media kernels fold the media's code away in device code only: the host's copies of the
// shared functions stay the same in every translation unit.
#if defined(PHOTON_KERNELS_WITHOUT_MEDIA) && defined(__CUDA_ARCH__)
#define PH_SCENE_HAS_MEDIA false
#endif
#include "stages.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/system/error.h"
#include "cuda_check.h"
#include "shared/denoise.h"
#include "shared/reproject.h"
#include "shared/eye_trace.h"
#include "shared/gather.h"
#include "shared/photon_map.h"
#include "shared/photon_trace.h"
#include "shared/progressive.h"
#include "shared/sppm.h"

namespace photon {
namespace PHOTON_KERNEL_NAMESPACE {

// Every kernel takes the frame's Bindings (buffer pointers and FrameParams, 672 bytes) by value as
// a __grid_constant__: shared code reaches it through a reference, and without the qualifier nvcc
// may copy the whole parameter to each thread's local memory and read every pointer and
// parameter from there (it did in tracePixels: a 1,056-byte stack frame, 143 local loads).

// The gather is bound by memory latency: more resident warps hide more of it. With blocks of up to
// 256 threads, 4 per SM leaves 64 registers a thread; final gather needs more and gets them.
constexpr int kGatherThreads = 256;
// (sppm has a kernel of its own, gatherSppmKernel, under LaunchConfig::gatherRegisters.)
constexpr int gatherMinBlocks(uint globalMode) { return globalMode == GLOBAL_DIRECT ? 4 : 1; }

// At most 64 registers (4 blocks of 256 on an SM): the traversal's stack would otherwise cost a
// quarter of the resident warps for a few spilled values. (On the H100, 80 registers measured 3-6%
// slower on meshes and 86 13-26% slower everywhere: docs/performance.md, session 12.)
__global__ void __launch_bounds__(256, 4) tracePhotonsKernel(const __grid_constant__ Bindings b) {
    tracePhotonPool(b);
}

// The stored photons of all maps as one range: photon k of it is photon i of map m (returned),
// counting the maps in order.
__device__ inline uint storedPhotonsOfAllMaps(const Bindings& b) {
    uint n = 0u;
    for (uint m = 0u; m < MAP_COUNT; ++m) {
        n += storedPhotons(b, m);
    }
    return n;
}

__device__ inline uint mapOfStoredPhoton(const Bindings& b, uint k, uint& i) {
    i = k;
    for (uint m = 0u; m + 1u < MAP_COUNT; ++m) {
        uint n = storedPhotons(b, m);
        if (i < n) {
            return m;
        }
        i -= n;
    }
    return MAP_COUNT - 1u;
}

__global__ void countCellsKernel(const __grid_constant__ Bindings b) {
    uint n = storedPhotonsOfAllMaps(b);
    for (uint k = blockIdx.x * blockDim.x + threadIdx.x; k < n; k += gridDim.x * blockDim.x) {
        uint i;
        uint map = mapOfStoredPhoton(b, k, i);
        countPhotonCell(b, map, i);
    }
}

__global__ void scatterPhotonsKernel(const __grid_constant__ Bindings b) {
    uint n = storedPhotonsOfAllMaps(b);
    for (uint k = blockIdx.x * blockDim.x + threadIdx.x; k < n; k += gridDim.x * blockDim.x) {
        uint i;
        uint map = mapOfStoredPhoton(b, k, i);
        scatterPhoton(b, map, i);
    }
}

// The deterministic build's steps (photon_map.h), over the places of the stored photons.
enum OrderStep : uint { kScatterIds, kRank, kMerge };

template <OrderStep Step>
__global__ void orderStepKernel(const __grid_constant__ Bindings b) {
    uint n = storedPhotonsOfAllMaps(b);
    for (uint k = blockIdx.x * blockDim.x + threadIdx.x; k < n; k += gridDim.x * blockDim.x) {
        uint i;
        uint map = mapOfStoredPhoton(b, k, i);
        if constexpr (Step == kScatterIds) {
            scatterPhotonId(b, map, i);
        } else if constexpr (Step == kRank) {
            rankInChunk(b, map, i);
        } else {
            mergeChunks(b, map, i);
        }
    }
}

__device__ inline bool pixelOf(const Bindings& b, uint& pixel) {
    uint x = blockIdx.x * blockDim.x + threadIdx.x;
    uint y = blockIdx.y * blockDim.y + threadIdx.y;
    pixel = y * b.params.width + x;
    return x < b.params.width && y < b.params.height;
}

// At most 168 registers, for 384 threads an SM (3 blocks of 16x8) instead of 256: the eye path's
// spills (1.3 KB, to L1) cost less than the warps its 221 registers left idle (docs/performance.md,
// issue 19; on the H100 in session 12, 128 registers cost 44% on the Cornell box, 221 23%).
__global__ void __maxnreg__(168) tracePixelsKernel(const __grid_constant__ Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        b.hitPoints[p] = tracePixel(b, p);
    }
}

__global__ void tracePrimaryRaysKernel(const __grid_constant__ Bindings b, uint* hits) {
    uint p;
    uint hit = pixelOf(b, p) ? tracePrimaryRay(b, p) : 0u;
    uint blockHits = __syncthreads_count(hit);
    if (threadIdx.x == 0 && threadIdx.y == 0 && blockHits > 0) {
        atomicAdd(hits, blockHits);
    }
}

// One kernel per estimator, global mode and sppm start: constants fold away the others' code (the
// k-nearest heap, final gather), which would otherwise cost registers and stack in every variant.
template <uint Estimator, uint GlobalMode, bool SppmStart>
__global__ void __launch_bounds__(kGatherThreads, gatherMinBlocks(GlobalMode)) gatherKernel(const __grid_constant__ Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        b.frameRadiance[p] = gatherStage(b, p, Estimator, GlobalMode, SppmStart);
    }
}

// The sppm gather under a register cap of its own (LaunchConfig::gatherRegisters).
template <bool SppmStart, int Registers>
__global__ void __maxnreg__(Registers) gatherSppmKernel(const __grid_constant__ Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        b.frameRadiance[p] = gatherStage(b, p, ESTIMATOR_SPPM, GLOBAL_DIRECT, SppmStart);
    }
}

__global__ void accumulateKernel(const __grid_constant__ Bindings b) {
    uint p;
    if (pixelOf(b, p)) {
        accumulateStage(b, p);
    }
}

__global__ void reprojectKernel(const __grid_constant__ Bindings b, uint pass) {
    uint p;
    if (pixelOf(b, p)) {
        reprojectPass(b, p, pass);
    }
}

__global__ void denoiseKernel(const __grid_constant__ Bindings b, uint pass) {
    uint p;
    if (pixelOf(b, p)) {
        denoisePass(b, p, pass);
    }
}

dim3 tileGrid(const Bindings& b, std::uint32_t x, std::uint32_t y) {
    return dim3((b.params.width + x - 1) / x, (b.params.height + y - 1) / y);
}

dim3 pixelGrid(const Bindings& b, const LaunchConfig& c) { return tileGrid(b, c.pixelBlockX, c.pixelBlockY); }

dim3 eyeGrid(const Bindings& b, const LaunchConfig& c) { return tileGrid(b, c.eyeBlockX, c.eyeBlockY); }

// Calls launch(std::integral_constant<int, R>) for the cap R among the kernels' compiled `Caps`
// that `registers` names. The parity kernels are compiled for the first (the default) alone.
template <int... Caps, typename Launch>
void withRegisters(std::uint32_t registers, const char* stage, Launch&& launch) {
#ifdef PHOTON_PARITY_KERNELS
    constexpr int kDefault[] = {Caps...};
    (void)registers;
    launch(std::integral_constant<int, kDefault[0]>());
    (void)stage;
#else
    bool found = ((registers == std::uint32_t(Caps) ? (launch(std::integral_constant<int, Caps>()), true) : false) || ...);
    if (!found) {
        throw std::logic_error(std::string(stage) + ": no kernel compiled for " + std::to_string(registers) + " registers");
    }
#endif
}

// The blocks of tracePhotonsKernel a device holds at once, for a block size: asked of the
// occupancy API once per device and size (a frame would otherwise ask it every time).
uint residentPhotonBlocks(uint blockSize) {
    struct Entry {
        int device;
        uint blockSize;
        uint blocks;
    };
    static std::mutex mutex;
    static std::vector<Entry> known;
    int device = 0;
    CUDA_CHECK(cudaGetDevice(&device), "tracePhotons");
    std::lock_guard<std::mutex> lock(mutex);
    for (const Entry& e : known) {
        if (e.device == device && e.blockSize == blockSize) {
            return e.blocks;
        }
    }
    int processors = 0;
    int resident = 0;
    CUDA_CHECK(cudaDeviceGetAttribute(&processors, cudaDevAttrMultiProcessorCount, device), "tracePhotons");
    CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&resident, tracePhotonsKernel, int(blockSize), 0),
               "tracePhotons");
    known.push_back({device, blockSize, uint(std::max(processors * resident, 1))});
    return known.back().blocks;
}

// Paths [0, pathCount), appending photons to the maps: as many blocks of the pool as the device
// holds at once (more would only start once the paths are taken), fewer for fewer paths.
void tracePhotons(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    uint paths = b.params.pathCount;
    if (paths == 0) {
        return;
    }
    uint blocks = std::min((paths + c.photonBlock - 1) / c.photonBlock, residentPhotonBlocks(c.photonBlock));
    tracePhotonsKernel<<<blocks, c.photonBlock, 0, s>>>(b);
    CUDA_CHECK_LAUNCH("tracePhotons");
}

// Run by the backend in its steps (countCells, its scan, then scatterPhotons or orderPhotons).
constexpr StageLaunch buildGrid = nullptr;

void countCells(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    countCellsKernel<<<c.gridBlocks, 256, 0, s>>>(b);
    CUDA_CHECK_LAUNCH("grid build (count)");
}

void scatterPhotons(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    scatterPhotonsKernel<<<c.gridBlocks, 256, 0, s>>>(b);
    CUDA_CHECK_LAUNCH("grid build (scatter)");
}

void orderPhotons(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    orderStepKernel<kScatterIds><<<c.gridBlocks, 256, 0, s>>>(b);
    CUDA_CHECK_LAUNCH("grid build (scatter ids)");
    orderStepKernel<kRank><<<c.gridBlocks, 256, 0, s>>>(b);
    CUDA_CHECK_LAUNCH("grid build (rank)");
    orderStepKernel<kMerge><<<c.gridBlocks, 256, 0, s>>>(b);
    CUDA_CHECK_LAUNCH("grid build (merge)");
}

void tracePixels(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    tracePixelsKernel<<<eyeGrid(b, c), dim3(c.eyeBlockX, c.eyeBlockY), 0, s>>>(b);
    CUDA_CHECK_LAUNCH("tracePixels");
}

template <uint Estimator>
void gatherWith(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    dim3 grid = pixelGrid(b, c);
    dim3 block(c.pixelBlockX, c.pixelBlockY);
    if constexpr (Estimator == ESTIMATOR_SPPM) {
        // sppm is direct mode only (validated on the host).
        if (b.params.globalMode != GLOBAL_DIRECT) {
            throw std::logic_error("CUDA gather: sppm in global mode " + std::to_string(b.params.globalMode));
        }
        bool start = sppmStarts(Estimator, b.params.view, b.params.accumulated);
        withRegisters<80, 64, 128>(c.gatherRegisters, "gather", [&](auto registers) {
            constexpr int kCap = decltype(registers)::value;
            if (start) {
                gatherSppmKernel<true, kCap><<<grid, block, 0, s>>>(b);
            } else {
                gatherSppmKernel<false, kCap><<<grid, block, 0, s>>>(b);
            }
        });
        return;
    }
    switch (b.params.globalMode) {
        case GLOBAL_DIRECT: gatherKernel<Estimator, GLOBAL_DIRECT, false><<<grid, block, 0, s>>>(b); break;
        case GLOBAL_FINAL_GATHER: gatherKernel<Estimator, GLOBAL_FINAL_GATHER, false><<<grid, block, 0, s>>>(b); break;
        default: throw std::logic_error("CUDA gather: unknown global mode " + std::to_string(b.params.globalMode));
    }
}

void gather(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    static_assert(ESTIMATOR_COUNT == 5, "a new estimator needs its gather kernel here");
    switch (b.params.estimator) {
        case ESTIMATOR_CELL: gatherWith<ESTIMATOR_CELL>(b, c, s); break;
        case ESTIMATOR_RADIUS:
        case ESTIMATOR_PROGRESSIVE: gatherWith<ESTIMATOR_RADIUS>(b, c, s); break;  // the same estimate
        case ESTIMATOR_KNN: gatherWith<ESTIMATOR_KNN>(b, c, s); break;
        case ESTIMATOR_SPPM: gatherWith<ESTIMATOR_SPPM>(b, c, s); break;
        default: throw std::logic_error("CUDA gather: unknown estimator " + std::to_string(b.params.estimator));
    }
    CUDA_CHECK_LAUNCH("gather");
}

void tracePrimaryRays(const Bindings& b, std::uint32_t* hits, const LaunchConfig& c, cudaStream_t s) {
    tracePrimaryRaysKernel<<<eyeGrid(b, c), dim3(c.eyeBlockX, c.eyeBlockY), 0, s>>>(b, hits);
    CUDA_CHECK_LAUNCH("tracePrimaryRays");
}

// Its passes in order, one launch each (restore reads what save wrote of other pixels).
void reproject(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    if ((b.params.flags & FLAG_REPROJECT) == 0u) {
        return;
    }
    for (uint pass = 0; pass < REPROJECT_PASS_COUNT; ++pass) {
        reprojectKernel<<<pixelGrid(b, c), dim3(c.pixelBlockX, c.pixelBlockY), 0, s>>>(b, pass);
        CUDA_CHECK_LAUNCH("reproject");
    }
}

void accumulate(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    accumulateKernel<<<pixelGrid(b, c), dim3(c.pixelBlockX, c.pixelBlockY), 0, s>>>(b);
    CUDA_CHECK_LAUNCH("accumulate");
}

// Its passes in order, one launch each (each reads its neighbours' results of the one before).
void denoise(const Bindings& b, const LaunchConfig& c, cudaStream_t s) {
    if ((b.params.flags & FLAG_DENOISE) == 0u) {
        return;
    }
    for (uint pass = 0; pass < DENOISE_PASS_COUNT; ++pass) {
        denoiseKernel<<<pixelGrid(b, c), dim3(c.pixelBlockX, c.pixelBlockY), 0, s>>>(b, pass);
        CUDA_CHECK_LAUNCH("denoise");
    }
}

}  // namespace PHOTON_KERNEL_NAMESPACE

#define PH_STAGE_LAUNCH(NAME, id, name, label) PHOTON_KERNEL_NAMESPACE::name,
const StageKernels PHOTON_KERNEL_TABLE = {
    {PH_STAGES(PH_STAGE_LAUNCH)},
    PHOTON_KERNEL_NAMESPACE::countCells,
    PHOTON_KERNEL_NAMESPACE::scatterPhotons,
    PHOTON_KERNEL_NAMESPACE::orderPhotons,
    PHOTON_KERNEL_NAMESPACE::tracePrimaryRays,
};

}  // namespace photon
