#include "core/system/zeroed_memory.h"

#include <cstdlib>
#include <new>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace photon {

namespace {
// Smaller arrays come from calloc (which maps large ones itself, but not aligned for huge pages).
constexpr std::size_t kMappedBytes = std::size_t(2) << 20;
}  // namespace

ZeroedMemory::ZeroedMemory(std::size_t bytes) : bytes_(bytes) {
    if (bytes == 0) {
        return;
    }
#if defined(__linux__)
    if (bytes >= kMappedBytes) {
        // Anonymous pages are zero. Linux places a mapping of 2 MB or more on a 2 MB boundary
        // where it can, and the advice asks for huge pages there (THP's "madvise" mode); where it
        // declines, the pages are ordinary ones, still zero and still faulted in only when used.
        void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) {
            throw std::bad_alloc();
        }
        madvise(p, bytes, MADV_HUGEPAGE);
        data_ = p;
        mapped_ = true;
        return;
    }
#endif
    static_assert(alignof(std::max_align_t) >= 16, "calloc's memory holds 16-byte vectors");
    data_ = std::calloc(bytes, 1);
    if (data_ == nullptr) {
        throw std::bad_alloc();
    }
}

ZeroedMemory::~ZeroedMemory() { release(); }

ZeroedMemory::ZeroedMemory(ZeroedMemory&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)), bytes_(std::exchange(other.bytes_, 0)), mapped_(other.mapped_) {}

ZeroedMemory& ZeroedMemory::operator=(ZeroedMemory&& other) noexcept {
    if (this != &other) {
        release();
        data_ = std::exchange(other.data_, nullptr);
        bytes_ = std::exchange(other.bytes_, 0);
        mapped_ = other.mapped_;
    }
    return *this;
}

void ZeroedMemory::release() {
    if (data_ == nullptr) {
        return;
    }
#if defined(__linux__)
    if (mapped_) {
        munmap(data_, bytes_);
        data_ = nullptr;
        return;
    }
#endif
    std::free(data_);
    data_ = nullptr;
}

}  // namespace photon
