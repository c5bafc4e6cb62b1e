#include "interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

#include "core/system/output_file.h"

namespace photon {
namespace {

// Read and written in a signal handler: lock-free atomics only.
std::atomic<int> gSignal{0};
static_assert(std::atomic<int>::is_always_lock_free, "the interrupt flag must be lock-free");

extern "C" void onSignal(int signo) {
    int expected = 0;
    if (gSignal.compare_exchange_strong(expected, signo)) {
        return;  // the first: the render loop stops after its frame
    }
    // The second: go now. unlink() and _exit() are async-signal-safe.
    removePendingOutput();
    _exit(128 + signo);
}

}  // namespace

void installInterruptHandlers() {
    struct sigaction action;
    std::memset(&action, 0, sizeof action);
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    // Restarted system calls: a signal does not make a read or write fail with EINTR.
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

int interruptSignal() { return gSignal.load(); }

}  // namespace photon
