// Host memory for large arrays. On Linux with transparent huge pages in "madvise" mode (Debian's
// default), memory asked for it comes in 2 MB pages, so that its first writes fault once per 2 MB
// instead of once per 4 KB; Embree's builders do the same. On the 2-core development VM, where a
// page fault costs microseconds, that is a third of a 10M-triangle BVH build (docs/performance.md).
#pragma once

#include <cstddef>

namespace photon {

// Asks for huge pages for [data, data + bytes): memory just allocated and not yet written (a
// vector after reserve(), an array after new[]); pages already touched stay as they are. Only
// arrays of several megabytes gain. Does nothing where the system has no such advice.
void adviseHugePages(const void* data, std::size_t bytes);

// Zeroed memory taken straight from the system: its pages read zero until first written and cost
// nothing until then (no fill pass, and an array sized for a budget costs what is used of it),
// in huge pages where granted. The CPU device's buffers live in it: a vector's zero fill took 0.3 s
// of a 640 × 480 render's start on the development VM, and its first frame's faults 0.15 s more.
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
