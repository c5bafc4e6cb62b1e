// Zeroed memory for large arrays, taken straight from the system: its pages read zero until first
// written and cost nothing until then (no fill pass, and an array sized for a budget costs what is
// used of it), and they come as 2 MB pages where the kernel has transparent huge pages, so that
// first writes fault once per 2 MB instead of once per 4 KB. The CPU device's buffers live in it:
// on the 2-core development VM, where a page fault costs microseconds, a vector's zero fill took
// 0.3 s of a 640 × 480 render's start and its first frame's faults 0.15 s more (docs/performance.md).
#pragma once

#include <cstddef>

namespace photon {

class ZeroedMemory {
public:
    ZeroedMemory() = default;
    explicit ZeroedMemory(std::size_t bytes);  // throws std::bad_alloc
    ~ZeroedMemory();
    ZeroedMemory(ZeroedMemory&& other) noexcept;
    ZeroedMemory& operator=(ZeroedMemory&& other) noexcept;
    ZeroedMemory(const ZeroedMemory&) = delete;
    ZeroedMemory& operator=(const ZeroedMemory&) = delete;

    void* data() const { return data_; }     // aligned to at least 16 bytes; null when empty
    std::size_t bytes() const { return bytes_; }

private:
    void release();
    void* data_ = nullptr;
    std::size_t bytes_ = 0;
    bool mapped_ = false;  // from mmap (else calloc)
};

}  // namespace photon
