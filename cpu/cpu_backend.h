// The CPU reference backend: every stage is a parallelFor over shared/ functions on all cores.
// Its results do not depend on the number of threads: photons are collected per fixed chunk and
// concatenated in chunk order, and the grid is built by a stable counting sort.
#pragma once

#include <memory>

#include "core/backend.h"

namespace photon {

std::unique_ptr<Backend> createCpuBackend();

}  // namespace photon
