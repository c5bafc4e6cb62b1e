#include "core/frame/collective.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>

namespace photon {
namespace {

class HostCollective final : public Collective {
public:
    Exchange gatherPhotons(const std::vector<Device*>& devices, const std::vector<FrameParams>& params,
                           std::vector<FrameResult>& results) override {
        auto start = std::chrono::steady_clock::now();
        Exchange exchange;
        Device& root = *devices[0];
        std::uint32_t* total = results[0].counters;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& grid = params[0].grids[m];
            std::uint32_t held = std::min(total[COUNTER_STORED + m], grid.photonCapacity);
            for (std::size_t d = 1; d < devices.size(); ++d) {
                const std::uint32_t* counters = results[d].counters;
                const GridParams& theirs = params[d].grids[m];
                std::uint32_t stored = std::min(counters[COUNTER_STORED + m], theirs.photonCapacity);
                std::uint32_t moved = std::min(stored, grid.photonCapacity - held);
                if (moved > 0) {
                    staging_.resize(moved);
                    std::uint64_t bytes = std::uint64_t(moved) * sizeof(Photon);
                    devices[d]->readBuffer(BINDING_PHOTONS, std::uint64_t(theirs.photonOffset) * sizeof(Photon), bytes,
                                           staging_.data());
                    root.writeBuffer(BINDING_PHOTONS, std::uint64_t(grid.photonOffset + held) * sizeof(Photon), bytes,
                                     staging_.data());
                    exchange.bytes += bytes;
                    held += moved;
                }
                // Photons beyond the capacity count as stored, as on one device: the map grows.
                total[COUNTER_STORED + m] += counters[COUNTER_STORED + m];
            }
        }
        for (std::size_t d = 1; d < devices.size(); ++d) {
            total[COUNTER_ENVIRONMENT_PATHS] += results[d].counters[COUNTER_ENVIRONMENT_PATHS];
            total[COUNTER_ENVIRONMENT_HITS] += results[d].counters[COUNTER_ENVIRONMENT_HITS];
        }
        root.writeBuffer(BINDING_COUNTERS, 0, sizeof(results[0].counters), total);
        exchange.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return exchange;
    }

private:
    std::vector<Photon> staging_;
};

}  // namespace

std::unique_ptr<Collective> createHostCollective() { return std::make_unique<HostCollective>(); }

bool launchedByMpi() {
    for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
        const char* value = std::getenv(name);
        if (value != nullptr && std::atoi(value) > 1) {
            return true;
        }
    }
    return false;
}

std::uint32_t launchedRank() {
    for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"}) {
        if (const char* value = std::getenv(name)) {
            return static_cast<std::uint32_t>(std::strtoul(value, nullptr, 10));
        }
    }
    return 0;
}

}  // namespace photon
