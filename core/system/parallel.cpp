#include "core/system/parallel.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <utility>
#include <mutex>
#include <thread>
#include <vector>

namespace photon {
namespace {

class ThreadPool {
public:
    ThreadPool() {
        unsigned n = std::max(1u, std::thread::hardware_concurrency());
        limit_ = n;
        for (unsigned i = 1; i < n; ++i) {
            workers_.emplace_back([this, i] { workerLoop(i); });
        }
    }

    ~ThreadPool() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : workers_) {
            t.join();
        }
    }

    unsigned threads() const { return static_cast<unsigned>(workers_.size() + 1); }

    // The threads that take chunks from now on (the caller's and workers 1 .. limit - 1).
    unsigned limit() const { return limit_.load(); }
    void setLimit(unsigned n) {
        std::lock_guard<std::mutex> one(runMutex_);  // not while a parallelFor runs
        limit_.store(std::clamp(n, 1u, threads()));
    }

    // Returns only once every worker is done with the body; an exception thrown by any chunk
    // (std::bad_alloc, say) stops the handing out of chunks and is rethrown here, after that.
    void run(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body) {
        std::lock_guard<std::mutex> one(runMutex_);  // one parallelFor at a time
        {
            std::lock_guard<std::mutex> lock(mutex_);
            body_ = &body;
            count_ = count;
            grain_ = std::max<std::size_t>(grain, 1);
            next_.store(0);
            failure_ = nullptr;
            active_ = workers_.size();
            generation_ += 1;
        }
        wake_.notify_all();
        work();
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [this] { return active_ == 0; });
        body_ = nullptr;
        if (failure_) {
            std::rethrow_exception(std::exchange(failure_, nullptr));
        }
    }

private:
    void work() {
        for (;;) {
            std::size_t begin = next_.fetch_add(grain_);
            if (begin >= count_) {
                return;
            }
            try {
                (*body_)(begin, std::min(begin + grain_, count_));
            } catch (...) {
                std::lock_guard<std::mutex> lock(mutex_);
                if (!failure_) {
                    failure_ = std::current_exception();
                }
                next_.store(count_);
                return;
            }
        }
    }

    void workerLoop(unsigned index) {
        std::uint64_t seen = 0;
        for (;;) {
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
                if (stopping_) {
                    return;
                }
                seen = generation_;
            }
            if (index < limit_.load()) {
                work();
            }
            {
                std::lock_guard<std::mutex> lock(mutex_);
                active_ -= 1;
            }
            done_.notify_one();
        }
    }

    std::vector<std::thread> workers_;
    std::mutex runMutex_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t, std::size_t)>* body_ = nullptr;
    std::size_t count_ = 0;
    std::size_t grain_ = 1;
    std::atomic<std::size_t> next_{0};
    std::atomic<unsigned> limit_{1};
    std::size_t active_ = 0;
    std::uint64_t generation_ = 0;
    std::exception_ptr failure_;
    bool stopping_ = false;
};

ThreadPool& pool() {
    static ThreadPool instance;
    return instance;
}

}  // namespace

void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body) {
    if (count == 0) {
        return;
    }
    if (count <= grain) {
        body(0, count);
        return;
    }
    pool().run(count, grain, body);
}

unsigned workerThreads() { return pool().threads(); }

unsigned threadLimit() { return pool().limit(); }

void setThreadLimit(unsigned threads) { pool().setLimit(threads == 0 ? pool().threads() : threads); }

}  // namespace photon
