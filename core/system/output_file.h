// Files Photon writes (images, stats, benchmark tables) appear whole or not at all: the bytes go to
// a temporary file in the target's folder, which is renamed over the target only after every write,
// the flush to disk and the close have succeeded. A failure says why (the OS's reason) and leaves
// nothing behind. checkOutputPath() finds what can be known before any work: a missing or
// read-only folder, a target that is a directory or a device.
#pragma once

#include <string>

namespace photon {

// Throws InputError "<path>: <reason>" if `path` cannot be written. `what` names the file for
// messages ("image", "stats").
void checkOutputPath(const std::string& path, const char* what);

// Writes `bytes` to `path` atomically; throws RuntimeError "<path>: cannot write <what>: <reason>"
// (InputError for the problems checkOutputPath finds).
void writeOutputFile(const std::string& path, const std::string& bytes, const char* what);

// Removes the temporary files of the writes in progress (those whose rename has not happened),
// for a signal handler that ends the process: async-signal-safe (atomics and unlink() only).
void removePendingOutput();

}  // namespace photon
