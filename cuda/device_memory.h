// Owning handles for device memory (cudaMalloc) and pinned host memory (cudaMallocHost), the
// seed's cudaHostAlloc suggestion: copies from pinned memory run at full bus speed and can be
// asynchronous.
#pragma once

#include <cuda_runtime.h>

#include <cstddef>
#include <utility>

#include "cuda_check.h"

namespace photon {

template <typename T, bool Pinned>
class CudaArray {
public:
    CudaArray() = default;
    CudaArray(const CudaArray&) = delete;
    CudaArray& operator=(const CudaArray&) = delete;
    CudaArray(CudaArray&& o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
    CudaArray& operator=(CudaArray&& o) noexcept {
        std::swap(data_, o.data_);
        std::swap(size_, o.size_);
        return *this;
    }
    ~CudaArray() { release(); }

    // Reallocates to hold n elements (contents are not kept). n = 0 frees.
    void resize(std::size_t n, const char* what) {
        if (n == size_) {
            return;
        }
        release();
        if (n > 0) {
            void* p = nullptr;
            if constexpr (Pinned) {
                CUDA_CHECK(cudaMallocHost(&p, n * sizeof(T)), what);
            } else {
                CUDA_CHECK(cudaMalloc(&p, n * sizeof(T)), what);
            }
            data_ = static_cast<T*>(p);
            size_ = n;
        }
    }

    T* data() const { return data_; }
    std::size_t size() const { return size_; }
    std::size_t bytes() const { return size_ * sizeof(T); }
    T& operator[](std::size_t i) const { return data_[i]; }

private:
    void release() {
        if (data_) {
            if constexpr (Pinned) {
                cudaFreeHost(data_);
            } else {
                cudaFree(data_);
            }
        }
        data_ = nullptr;
        size_ = 0;
    }

    T* data_ = nullptr;
    std::size_t size_ = 0;
};

template <typename T>
using DeviceArray = CudaArray<T, false>;
template <typename T>
using PinnedArray = CudaArray<T, true>;

}  // namespace photon
