// The outside of every Photon program: errors become one line on stderr and an exit code
// (0 success, 2 bad input, 1 runtime failure).
#pragma once

#include <cstdio>
#include <exception>

#include "core/error.h"

namespace photon {

template <typename Run>
int runProgram(const char* name, Run run) {
    try {
        return run();
    } catch (const InputError& e) {
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", name, e.what());
        return 1;
    }
}

}  // namespace photon
