#include "core/system/host_memory.h"

#include <cstdint>
#include <cstdlib>
#include <new>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace photon {

namespace {
constexpr std::size_t kHugePageBytes = std::size_t(2) << 20;
constexpr std::size_t kAdvisedBytes = 2 * kHugePageBytes;  // smaller arrays hold no whole huge page worth it
}  // namespace

void adviseHugePages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (data == nullptr || bytes < kAdvisedBytes) {
        return;
    }
    // The advice is per page: the range's first and last pages may hold other allocations too,
    // which only become eligible for huge pages as well.
    static const auto kPage = std::uintptr_t(sysconf(_SC_PAGESIZE));
    auto first = reinterpret_cast<std::uintptr_t>(data) & ~(kPage - 1);
    auto last = (reinterpret_cast<std::uintptr_t>(data) + bytes + kPage - 1) & ~(kPage - 1);
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

ZeroedMemory::ZeroedMemory(std::size_t bytes) : bytes_(bytes) {
    if (bytes == 0) {
        return;
    }
#if defined(__linux__)
    if (bytes >= kHugePageBytes) {
        // Anonymous pages are zero. Linux places a mapping of 2 MB or more on a 2 MB boundary
        // where it can, and the advice asks for huge pages there (THP's "madvise" mode); where it
        // declines, the pages are ordinary ones, still zero and still faulted in only when used.
        void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) {
            throw std::bad_alloc();
        }
        adviseHugePages(p, bytes);
        data_ = p;
        mapped_ = true;
        return;
    }
#endif
    // Smaller arrays from calloc (which maps large ones itself, but not on 2 MB boundaries).
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
