// A vector sized on a helper thread while the caller goes on working: a vector's resize zeroes
// its memory on one thread, and the first touch of fresh memory is a page fault per 4 KiB (at 10M
// triangles tens of milliseconds an array on the 2-core machine, fewer in huge pages). The BVH
// build sizes its output arrays so while it builds.
#pragma once

#include <exception>
#include <system_error>
#include <thread>
#include <vector>

#include "core/system/host_memory.h"

namespace photon {

template <class T>
class SizedOnHelper {
public:
    // Reserves `capacity` (address space only; the pages are touched when used) and resizes to
    // `size` on the helper, or here and now when no thread can be started.
    SizedOnHelper(std::vector<T>& v, std::size_t capacity, std::size_t size) : v_(v) {
        auto work = [this, capacity, size] {
            try {
                v_.clear();
                v_.reserve(capacity);
                adviseHugePages(v_.data(), capacity * sizeof(T));
                v_.resize(size);
            } catch (...) {
                failure_ = std::current_exception();
            }
        };
        try {
            helper_ = std::thread(work);
        } catch (const std::system_error&) {
            work();
        }
    }
    ~SizedOnHelper() {
        if (helper_.joinable()) {
            helper_.join();
        }
    }
    SizedOnHelper(const SizedOnHelper&) = delete;
    SizedOnHelper& operator=(const SizedOnHelper&) = delete;

    // The vector, once the helper is done (its failure, such as bad_alloc, thrown here).
    std::vector<T>& get() {
        if (helper_.joinable()) {
            helper_.join();
        }
        if (failure_) {
            std::rethrow_exception(failure_);
        }
        return v_;
    }

private:
    std::vector<T>& v_;
    std::thread helper_;
    std::exception_ptr failure_;
};

}  // namespace photon
