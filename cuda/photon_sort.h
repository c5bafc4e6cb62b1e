// The deterministic grid build's sort: (cell key, photon id) pairs in ascending order by CUB's
// radix sort, which gives every cell its photons in canonical order (shared/photon_map.h).
#pragma once

#include <cuda_runtime.h>

#include <cstdint>

#include "device_memory.h"

namespace photon {

class PhotonSort {
public:
    // Room for sorting up to `count` photons; the bytes that takes.
    void reserve(std::uint32_t count);
    static std::uint64_t bytesFor(std::uint32_t count);

    std::uint64_t* keys() const { return keys_.data(); }
    std::uint32_t* indices() const { return indices_.data(); }

    // Sorts the first `count` keys (of `keyBits` bits) with their indices; returns the indices in
    // key order.
    const std::uint32_t* sort(std::uint32_t count, int keyBits, cudaStream_t stream);

private:
    DeviceArray<unsigned char> temp_;
    DeviceArray<std::uint64_t> keys_;
    DeviceArray<std::uint64_t> sortedKeys_;
    DeviceArray<std::uint32_t> indices_;
    DeviceArray<std::uint32_t> sortedIndices_;
    std::uint32_t reserved_ = 0;
};

}  // namespace photon
