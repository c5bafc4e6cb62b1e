#include "cell_scan.h"

#include <cub/device/device_scan.cuh>

namespace photon {

void CellScan::reserve(std::uint32_t count) {
    if (count <= reserved_) {
        return;
    }
    std::size_t bytes = 0;
    CUDA_CHECK(cub::DeviceScan::ExclusiveSum(nullptr, bytes, static_cast<const std::uint32_t*>(nullptr),
                                             static_cast<std::uint32_t*>(nullptr), count),
               "grid build (scan storage)");
    temp_.resize(bytes, "grid build (scan storage)");
    reserved_ = count;
}

void CellScan::exclusiveSum(const std::uint32_t* counts, std::uint32_t* starts, std::uint32_t count,
                            cudaStream_t stream) {
    std::size_t bytes = temp_.bytes();
    CUDA_CHECK(cub::DeviceScan::ExclusiveSum(temp_.data(), bytes, counts, starts, count, stream), "grid build (scan)");
}

}  // namespace photon
