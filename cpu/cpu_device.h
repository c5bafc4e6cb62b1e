// The CPU reference device: every stage is a parallelFor over shared/ functions on all cores.
// Its results do not depend on the number of threads: the photon pass appends with atomics (as
// the GPUs do), the grid build counts, scans and scatters them into cells, and then sorts each
// cell's photons by id, the canonical order (shared/photon_map.h) that no timing can change.
#pragma once

#include <memory>

#include "core/frame/device.h"

namespace photon {

std::unique_ptr<Device> createCpuDevice();

}  // namespace photon
