#include "cell_sort.h"

#include <cub/device/device_radix_sort.cuh>

namespace photon {
namespace {

__global__ void iotaKernel(std::uint32_t* v, std::uint32_t n) {
    std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) {
        v[i] = i;
    }
}

__global__ void gatherKernel(const std::uint32_t* order, const Photon* photons, Photon* sorted, std::uint32_t n) {
    std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < n) {
        sorted[i] = photons[order[i]];
    }
}

}  // namespace

void CellSort::reserve(std::uint32_t count) {
    if (count <= reserved_) {
        return;
    }
    std::size_t bytes = 0;
    CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, static_cast<const std::uint32_t*>(nullptr),
                                               static_cast<std::uint32_t*>(nullptr),
                                               static_cast<const std::uint32_t*>(nullptr),
                                               static_cast<std::uint32_t*>(nullptr), int(count)),
               "buildGrid (sort storage)");
    temp_.resize(bytes, "buildGrid (sort storage)");
    indices_.resize(count, "buildGrid (sort storage)");
    sortedKeys_.resize(count, "buildGrid (sort storage)");
    sortedIndices_.resize(count, "buildGrid (sort storage)");
    reserved_ = count;
}

void CellSort::sort(const std::uint32_t* keys, const Photon* photons, Photon* sorted, std::uint32_t count, int keyBits,
                    cudaStream_t stream) {
    if (count == 0) {
        return;
    }
    std::uint32_t blocks = (count + 255) / 256;
    iotaKernel<<<blocks, 256, 0, stream>>>(indices_.data(), count);
    CUDA_CHECK_LAUNCH("buildGrid (sort)");
    std::size_t bytes = temp_.bytes();
    CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp_.data(), bytes, keys, sortedKeys_.data(), indices_.data(),
                                               sortedIndices_.data(), int(count), 0, keyBits, stream),
               "buildGrid (sort)");
    gatherKernel<<<blocks, 256, 0, stream>>>(sortedIndices_.data(), photons, sorted, count);
    CUDA_CHECK_LAUNCH("buildGrid (sort)");
}

}  // namespace photon
