// Ctrl-C and kill during a render (issue 16). The first SIGINT or SIGTERM only sets a flag: the
// program finishes the frame in flight, writes what it has and exits 128 + the signal (130 for
// Ctrl-C). A second one ends the process at once with 128 + its signal, after removing the
// temporary file of an output being written (core/system/output_file.h): nothing half-written is left at
// an output's path, since outputs only get there by a rename of a whole file.
#pragma once

namespace photon {

// Installs the handlers (sigaction) for SIGINT and SIGTERM. Call once, early.
void installInterruptHandlers();

// The first signal received since installInterruptHandlers(), or 0.
int interruptSignal();

}  // namespace photon
