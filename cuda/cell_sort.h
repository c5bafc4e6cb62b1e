// The grid build's alternative to the counting sort's scatter: CUB's radix sort of (cell key,
// photon index) pairs, then a gather of the photons in key order. Kept to measure against the
// scatter (docs/performance.md); the counting sort is the default.
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "device_memory.h"
#include "shared/layout.h"

namespace photon {

class CellSort {
public:
    // Room for sorting up to `count` photons.
    void reserve(std::uint32_t count);
    // sorted[i] = photons[j] for the i-th smallest key[j], j < count; keys below 2^keyBits.
    void sort(const std::uint32_t* keys, const Photon* photons, Photon* sorted, std::uint32_t count, int keyBits,
              cudaStream_t stream);

private:
    DeviceArray<unsigned char> temp_;
    DeviceArray<std::uint32_t> indices_;
    DeviceArray<std::uint32_t> sortedKeys_;
    DeviceArray<std::uint32_t> sortedIndices_;
    std::uint32_t reserved_ = 0;
};

}  // namespace photon
