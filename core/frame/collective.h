// What the devices of one frame must share, exchanged between two of its stages. The frame's
// photon paths are split over the processes and, within each, over its devices by index range
// (PathSplit); each device traces its own, and the photons then meet in one device's maps (the
// first device of the first process, the leader), which builds the grid and runs the eye pass.
// Every process then receives the leader's counters, so that each renderer grows its maps and
// chooses its radii as the leader does. The host Collective joins the devices of one process; the
// MPI one (mpi_collective.h, where MPI is built) joins processes too.
//
// Why photons, and not each pixel's sums after a gather on every device: the photon maps' grid
// puts each cell's photons in id order (--deterministic), so the gathered maps are the maps one
// device would have built and the image is the same bit for bit, where per-device sums added
// afterwards round differently; and the bytes are alike (32 bytes a stored photon, about 1.1
// stored per path in the Cornell box, against an SppmPixel and a radiance a pixel for every
// device: docs/performance.md measures both).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/frame/device.h"
#include "core/frame/fingerprint.h"

namespace photon {

struct StopVote {
    int request = 0;    // the largest stop request of any process (0: none)
    bool stop = false;  // stop after this frame
};

struct Exchange {
    std::uint64_t bytes = 0;  // moved between devices this frame
    double ms = 0.0;          // host time the exchange took
};

class Collective {
public:
    virtual ~Collective() = default;

    // The processes rendering together (1: this one alone) and this one's place among them. The
    // first leads: it runs the frame after the exchange and holds the image.
    virtual std::uint32_t processes() const { return 1; }
    virtual std::uint32_t process() const { return 0; }
    bool leads() const { return process() == 0; }

    // After the photon pass, which device d ran over its own paths (params[d]; results[d] holds
    // its counters): every device's photons join the first device's maps after its own, up to
    // each map's capacity, and the first device's counters become the frame's: each map's
    // stored photons and the environment's paths summed over the devices, in results[0] and
    // written to the first device for the stages that follow (Device::beginStages(resume)).
    virtual Exchange gatherPhotons(const std::vector<Device*>& devices, const std::vector<FrameParams>& params,
                                   std::vector<FrameResult>& results) = 0;

    // After the leader ran the rest of the frame: its times and counters, in every process.
    virtual void shareResult(FrameResult& result) { (void)result; }

    // Before the first frame: every process must render the same scene with the same settings
    // (core/frame/fingerprint.h). Throws InputError in every process, naming the first process
    // and item that differ from the leader's; one process alone has nothing to compare.
    virtual void checkSameInputs(const std::vector<Fingerprint>& mine) { (void)mine; }

    // After each frame, in every process alike: whether to stop. `request` is this process's stop
    // request (0: none; else its reason, such as a signal's number) and `leaderDone` whether the
    // leader's render is over (its time is spent); only the leader's counts, so that the processes
    // stop after the same frame. Any process's request stops them all, and each learns the
    // largest request.
    virtual StopVote agreeToStop(int request, bool leaderDone) { return {request, request != 0 || leaderDone}; }
};

// The devices of one process, through host memory.
std::unique_ptr<Collective> createHostCollective();

// Whether an MPI launcher (mpirun, srun) started this process among others, and its rank there
// (0 when not launched so): before MPI starts, what a program needs to stay quiet but in rank 0.
bool launchedByMpi();
std::uint32_t launchedRank();

}  // namespace photon
