#include "core/render/mpi_collective.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <string>
#include <thread>
#include <vector>

#include "core/system/error.h"

namespace photon {
namespace {

void check(int code, const char* what) {
    if (code != MPI_SUCCESS) {
        char text[MPI_MAX_ERROR_STRING] = {};
        int length = 0;
        MPI_Error_string(code, text, &length);
        throw RuntimeError(std::string("MPI: ") + what + ": " + text);
    }
}

// Waits for a request without spinning: the processes that wait for the leader's eye pass (the
// frame's longest part) would otherwise take a core from it where they share a host.
void waitIdly(MPI_Request& request, const char* what) {
    for (;;) {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), what);
        if (done) {
            return;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
}

// MPI for the process's lifetime: initialized once, finalized at exit.
struct MpiSession {
    MpiSession() {
        int initialized = 0;
        MPI_Initialized(&initialized);
        if (!initialized) {
            int provided = 0;
            check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "init");
            owned = true;
        }
    }
    ~MpiSession() {
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (owned && !finalized) {
            MPI_Finalize();
        }
    }
    bool owned = false;
};

class MpiCollective final : public Collective {
public:
    MpiCollective() : local_(createHostCollective()) {
        static MpiSession session;
        int rank = 0;
        int size = 1;
        check(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "rank");
        check(MPI_Comm_size(MPI_COMM_WORLD, &size), "size");
        rank_ = static_cast<std::uint32_t>(rank);
        size_ = static_cast<std::uint32_t>(size);
        counts_.resize(size_);
        offsets_.resize(size_);
    }

    std::uint32_t processes() const override { return size_; }
    std::uint32_t process() const override { return rank_; }

    // This process's devices into its first, then every process's photons into the leader's maps
    // in process order, and the counters summed there.
    Exchange gatherPhotons(const std::vector<Device*>& devices, const std::vector<FrameParams>& params,
                           std::vector<FrameResult>& results) override {
        Exchange exchange = local_->gatherPhotons(devices, params, results);
        auto start = std::chrono::steady_clock::now();
        Device& root = *devices.front();
        std::uint32_t* counters = results.front().counters;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& grid = params.front().grids[m];
            std::uint32_t held = std::min(counters[COUNTER_STORED + m], grid.photonCapacity);
            std::uint64_t bytes = leads() ? 0 : std::uint64_t(held) * sizeof(Photon);
            if (bytes > INT_MAX) {
                throw RuntimeError("MPI: " + std::to_string(held) + " photons of one map are more than one message carries");
            }
            sent_.resize(leads() ? 0 : held);
            if (!sent_.empty()) {
                root.readBuffer(BINDING_PHOTONS, std::uint64_t(grid.photonOffset) * sizeof(Photon), bytes, sent_.data());
            }
            int count = static_cast<int>(bytes);
            check(MPI_Gather(&count, 1, MPI_INT, counts_.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "photon counts");
            std::uint64_t received = 0;
            for (std::uint32_t r = 0; r < size_; ++r) {
                offsets_[r] = static_cast<int>(std::min<std::uint64_t>(received, INT_MAX));
                received += leads() ? std::uint64_t(counts_[r]) : 0u;
            }
            if (received > INT_MAX) {
                throw RuntimeError("MPI: the processes' photons of one map are more than one message carries");
            }
            received_.resize(received / sizeof(Photon));
            check(MPI_Gatherv(sent_.data(), count, MPI_BYTE, received_.data(), counts_.data(), offsets_.data(), MPI_BYTE, 0,
                              MPI_COMM_WORLD),
                  "photons");
            if (leads()) {
                auto moved = static_cast<std::uint32_t>(std::min<std::uint64_t>(received_.size(), grid.photonCapacity - held));
                if (moved > 0) {
                    root.writeBuffer(BINDING_PHOTONS, std::uint64_t(grid.photonOffset + held) * sizeof(Photon),
                                     std::uint64_t(moved) * sizeof(Photon), received_.data());
                }
            }
            exchange.bytes += leads() ? received : bytes;
        }
        // Each map's stored photons (those beyond the capacity too: the map grows) and the
        // environment's paths, summed.
        constexpr std::uint32_t kSummed = MAP_COUNT + 2;
        std::uint32_t mine[kSummed];
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            mine[m] = counters[COUNTER_STORED + m];
        }
        mine[MAP_COUNT] = counters[COUNTER_ENVIRONMENT_PATHS];
        mine[MAP_COUNT + 1] = counters[COUNTER_ENVIRONMENT_HITS];
        std::uint32_t sum[kSummed] = {};
        check(MPI_Reduce(mine, sum, kSummed, MPI_UINT32_T, MPI_SUM, 0, MPI_COMM_WORLD), "counters");
        if (leads()) {
            for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
                counters[COUNTER_STORED + m] = sum[m];
            }
            counters[COUNTER_ENVIRONMENT_PATHS] = sum[MAP_COUNT];
            counters[COUNTER_ENVIRONMENT_HITS] = sum[MAP_COUNT + 1];
            root.writeBuffer(BINDING_COUNTERS, 0, sizeof(results.front().counters), counters);
        }
        exchange.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return exchange;
    }

    void shareResult(FrameResult& result) override {
        MPI_Request requests[2];
        check(MPI_Ibcast(result.counters, COUNTER_COUNT, MPI_UINT32_T, 0, MPI_COMM_WORLD, &requests[0]), "frame counters");
        check(MPI_Ibcast(result.ms.ms, STAGE_COUNT, MPI_DOUBLE, 0, MPI_COMM_WORLD, &requests[1]), "frame times");
        waitIdly(requests[0], "frame counters");
        waitIdly(requests[1], "frame times");
    }

    // The leader gathers every process's hashes, finds the first process and item that differ and
    // tells all, so that every process refuses with the same line before any frame.
    void checkSameInputs(const std::vector<Fingerprint>& mine) override {
        std::vector<std::uint64_t> hashes;
        for (const Fingerprint& f : mine) {
            hashes.push_back(f.hash);
        }
        int count = static_cast<int>(hashes.size());
        std::vector<int> counts(size_), offsets(size_);
        check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "input counts");
        std::vector<std::uint64_t> all;
        if (leads()) {
            int total = 0;
            for (std::uint32_t r = 0; r < size_; ++r) {
                offsets[r] = total;
                total += counts[r];
            }
            all.resize(std::size_t(total));
        }
        check(MPI_Gatherv(hashes.data(), count, MPI_UINT64_T, all.data(), counts.data(), offsets.data(), MPI_UINT64_T, 0,
                          MPI_COMM_WORLD),
              "input hashes");
        int verdict[2] = {-1, -1};  // the first process that differs, and the item (-1: its build's items)
        for (std::uint32_t r = 1; leads() && r < size_ && verdict[0] < 0; ++r) {
            if (counts[r] != count) {
                verdict[0] = int(r);
                break;
            }
            for (int i = 0; i < count; ++i) {
                if (all[std::size_t(offsets[r] + i)] != hashes[std::size_t(i)]) {
                    verdict[0] = int(r), verdict[1] = i;
                    break;
                }
            }
        }
        check(MPI_Bcast(verdict, 2, MPI_INT, 0, MPI_COMM_WORLD), "input verdict");
        if (verdict[0] < 0) {
            return;
        }
        std::string who = "MPI process " + std::to_string(verdict[0]) + " of " + std::to_string(size_);
        if (verdict[1] < 0) {
            throw InputError(who + " runs another build of Photon than process 0 (its inputs are other items)");
        }
        const std::string& item = mine[std::size_t(verdict[1])].name;
        bool arrays = item.rfind("the scene's", 0) == 0;
        bool scene = item.rfind("the ", 0) == 0;  // the scene's arrays or the camera; else a setting's flag
        throw InputError(who + ": " + item + (arrays ? " differ" : " differs") + " from process 0's" +
                         (scene ? " (another scene file, or a stale copy of it or its models on that host?)"
                         : item == "--photons" ? " (where no photon count is given, each process's device chooses one: give it)"
                                               : " (give every process the same settings)"));
    }

    // One reduction: the largest request of any process, and the leader's end (the others send 0).
    StopVote agreeToStop(int request, bool leaderDone) override {
        int mine[2] = {request, leads() && leaderDone ? 1 : 0};
        int all[2] = {};
        check(MPI_Allreduce(mine, all, 2, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "stop vote");
        return {all[0], all[0] != 0 || all[1] != 0};
    }

private:
    std::unique_ptr<Collective> local_;
    // Kept from frame to frame: this process's photons of one map, and the leader's receipt.
    std::vector<Photon> sent_;
    std::vector<Photon> received_;
    std::vector<int> counts_;   // bytes from each process
    std::vector<int> offsets_;  // ... and where they go
    std::uint32_t rank_ = 0;
    std::uint32_t size_ = 1;
};

}  // namespace

std::unique_ptr<Collective> createMpiCollective() { return std::make_unique<MpiCollective>(); }

}  // namespace photon
