// Reading the files a user hands Photon (scenes, models, textures): regular files only, opened
// without blocking (a FIFO or a device is refused, never waited on), and no larger than a cap, so
// that /dev/zero, a pipe or a runaway file give one clear message instead of a hang.
#pragma once

#include <cstdint>
#include <string>

namespace photon {

// The cap on scene files: 256 MiB.
inline constexpr std::uint64_t kSceneFileLimit = std::uint64_t(256) << 20;

// The whole file; throws InputError "<path>: <reason>" if it is not a regular file, cannot be
// read (the OS's reason), or is larger than `limit` bytes. `what` names the kind of file for the
// messages ("scene file", "OBJ file").
std::string readInputFile(const std::string& path, std::uint64_t limit, const char* what);

// What a path is that is not a regular file, from its st_mode: "a directory", "a FIFO (named
// pipe)", ... (for messages).
const char* fileKind(unsigned mode);

}  // namespace photon
