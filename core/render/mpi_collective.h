// The Collective across processes, through MPI (OpenMPI from Debian: libopenmpi-dev), so that
// `mpirun -np N photon-render ...` renders one image with N processes, on one host or many: each
// process traces its share of every frame's photon paths on its own devices (joined in its first
// device by the host Collective), sends its photons to the first process (MPI_Gatherv), which
// runs the rest of the frame and sends back the frame's counters (MPI_Bcast). Built where CMake
// finds MPI (PHOTON_HAVE_MPI); createRenderer() takes it when launchedByMpi() (collective.h).
#pragma once

#include <memory>

#include "core/frame/collective.h"

namespace photon {

// Initializes MPI on first use (MPI_Finalize runs at exit); over MPI_COMM_WORLD.
std::unique_ptr<Collective> createMpiCollective();

}  // namespace photon
