// Exclusive prefix sum of the per-cell photon counts into cell starts, by CUB's DeviceScan.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "device_memory.h"

namespace photon {

class CellScan {
public:
    // Reserves CUB's temporary storage for scans of up to `count` entries.
    void reserve(std::uint32_t count);
    // starts[i] = Σ_{j<i} counts[j] for i < count.
    void exclusiveSum(const std::uint32_t* counts, std::uint32_t* starts, std::uint32_t count, cudaStream_t stream);

private:
    DeviceArray<unsigned char> temp_;
    std::uint32_t reserved_ = 0;
};

}  // namespace photon
