// Every CUDA call is checked; a failure names the stage it happened in and CUDA's reason.
#pragma once

#include <cuda_runtime.h>

#include <string>

#include "core/system/error.h"

namespace photon {

inline void cudaCheck(cudaError_t result, const char* call, const char* stage) {
    if (result != cudaSuccess) {
        throw RuntimeError(std::string("CUDA ") + stage + ": " + call + " failed: " + cudaGetErrorName(result) +
                           " (" + cudaGetErrorString(result) + ")");
    }
}

}  // namespace photon

// CUDA_CHECK(call, "stage"): throws RuntimeError if the call failed.
#define CUDA_CHECK(call, stage) ::photon::cudaCheck((call), #call, stage)
// After a kernel launch: launch errors now, execution errors at the next synchronisation.
#define CUDA_CHECK_LAUNCH(stage) ::photon::cudaCheck(cudaGetLastError(), "kernel launch", stage)
