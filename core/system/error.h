// The two kinds of failure the programs report: bad input from the user (exit code 2) and a
// runtime failure such as a backend that is not available (exit code 1). Messages are one line.
#pragma once

#include <stdexcept>
#include <string>

namespace photon {

// A malformed scene, an impossible setting, a file that cannot be read: the user can fix it.
struct InputError : std::runtime_error {
    explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

// Something failed while running: no such backend or device, out of device memory, a failed call.
struct RuntimeError : std::runtime_error {
    explicit RuntimeError(const std::string& what) : std::runtime_error(what) {}
};

// The text as one line a terminal shows as it is: UTF-8 passes, control characters (C0, DEL,
// C1) and bytes that are not UTF-8 become \xNN escapes; at most kMessageMax bytes, a longer line
// keeping its start and its end (where the reason is) around " ... [N bytes cut] ... ". Every
// message the programs print passes through it, so no input makes a line longer.
inline constexpr std::size_t kMessageMax = 1000;
std::string printable(const std::string& text);

// A token from a file as a message quotes it: 'token', cut to kQuotedTokenMax bytes (at a UTF-8
// character boundary) with "..." after, so that a 100000-digit number is not a 100 KB line.
inline constexpr std::size_t kQuotedTokenMax = 40;
std::string quote(const std::string& token);

}  // namespace photon
