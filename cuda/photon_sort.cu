#include "photon_sort.h"

#include <cub/device/device_radix_sort.cuh>

namespace photon {
namespace {

std::size_t tempBytes(std::uint32_t count) {
    std::size_t bytes = 0;
    CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, static_cast<const std::uint64_t*>(nullptr),
                                               static_cast<std::uint64_t*>(nullptr),
                                               static_cast<const std::uint32_t*>(nullptr),
                                               static_cast<std::uint32_t*>(nullptr), int(count)),
               "grid build (sort storage)");
    return bytes;
}

}  // namespace

std::uint64_t PhotonSort::bytesFor(std::uint32_t count) {
    return std::uint64_t(count) * 2 * (sizeof(std::uint64_t) + sizeof(std::uint32_t)) + tempBytes(count);
}

void PhotonSort::reserve(std::uint32_t count) {
    if (count <= reserved_) {
        return;
    }
    temp_.resize(tempBytes(count), "grid build (sort storage)");
    keys_.resize(count, "grid build (sort storage)");
    sortedKeys_.resize(count, "grid build (sort storage)");
    indices_.resize(count, "grid build (sort storage)");
    sortedIndices_.resize(count, "grid build (sort storage)");
    reserved_ = count;
}

const std::uint32_t* PhotonSort::sort(std::uint32_t count, int keyBits, cudaStream_t stream) {
    std::size_t bytes = temp_.bytes();
    CUDA_CHECK(cub::DeviceRadixSort::SortPairs(temp_.data(), bytes, keys_.data(), sortedKeys_.data(), indices_.data(),
                                               sortedIndices_.data(), int(count), 0, keyBits, stream),
               "grid build (sort)");
    return sortedIndices_.data();
}

}  // namespace photon
