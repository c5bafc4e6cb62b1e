// parallelFor over a pool of worker threads started once. Work is split into fixed chunks that
// threads claim in turn; results that depend on order are kept per chunk by the caller, so the
// outcome never depends on which thread ran what.
#pragma once

#include <cstddef>
#include <functional>

namespace photon {

// Calls body(begin, end) for consecutive chunks of [0, count) of at most `grain` items, on all
// hardware threads including the caller's. Returns when every chunk is done; if a chunk throws,
// no further chunks start and the exception reaches the caller once every thread has stopped.
void parallelFor(std::size_t count, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body);

// The pool's threads, the caller's included (one per hardware thread).
unsigned workerThreads();

// How many of them parallelFor uses (all unless set): 1 runs every chunk on the caller's thread,
// in order, as a reference for results that must not depend on the thread count, and for
// measuring how a stage scales. 0 restores all. Not to be called during a parallelFor.
unsigned threadLimit();
void setThreadLimit(unsigned threads);

}  // namespace photon
