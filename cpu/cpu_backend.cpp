#include "cpu_backend.h"

#include <algorithm>
#include <chrono>
#include <thread>
#include <vector>

#include "parallel.h"
#include "shared/bindings.h"
#include "shared/eye_trace.h"
#include "shared/gather.h"
#include "shared/grid.h"
#include "shared/photon_trace.h"
#include "shared/progressive.h"

namespace photon {
namespace {

constexpr std::size_t kPhotonChunk = 2048;  // photon paths per chunk of the photon pass
constexpr std::size_t kPixelChunk = 256;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

class CpuBackend final : public Backend {
public:
    std::string name() const override { return "cpu"; }

    std::string deviceName() const override {
        return "CPU (" + std::to_string(workerThreads()) + " threads)";
    }

    PhotonMaps readPhotonMaps() override {
        PhotonMaps maps;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& g = bindings_.params.grids[m];
            auto first = sorted_.begin() + g.photonOffset;
            maps.photons[m].assign(first, first + traced_[m].size());
            auto cells = cellStart_.begin() + g.cellOffset;
            maps.cellStart[m].assign(cells, cells + g.cellCount + 1);
        }
        return maps;
    }

    std::vector<HitPoint> readHitPoints() override { return hitPoints_; }

    Image readFrame() override { return toImage(frame_); }

protected:
    void uploadScene(const Scene& scene) override { scene_ = scene; }

    void allocate(const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) override {
        std::size_t pixels = std::size_t(width) * height;
        width_ = width;
        height_ = height;
        hitPoints_.assign(pixels, HitPoint{});
        frame_.assign(pixels, glm::vec4(0.0f));
        accumulation_.assign(pixels, glm::vec4(0.0f));
        cellStart_.assign(budget.totalCellEntries(), 0u);
        std::size_t chunks = (budget.totalPaths() + kPhotonChunk - 1) / kPhotonChunk;
        for (auto& perChunk : chunkPhotons_) {
            perChunk.assign(chunks, {});
        }
    }

    FrameStats runFrame(const FrameParams& params) override {
        bind(params);
        FrameStats stats;
        auto t = std::chrono::steady_clock::now();
        tracePhotons();
        stats.ms.tracePhotons = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        buildGrid();
        stats.ms.buildGrid = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        tracePixels();
        stats.ms.tracePixels = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        gather();
        stats.ms.gather = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        accumulate();
        stats.ms.accumulate = millisecondsSince(t);

        stats.emitted[MAP_GLOBAL] = params.globalPaths;
        stats.emitted[MAP_CAUSTIC] = params.causticPaths;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            stats.stored[m] = static_cast<std::uint32_t>(traced_[m].size());
            stats.capacity[m] = NONE;  // unbounded: the CPU appends to growing arrays
        }
        return stats;
    }

    Image readAccumulation() override { return toImage(accumulation_); }

private:
    void bind(const FrameParams& params) {
        Bindings& b = bindings_;
        b.params = params;
        bindSceneArrays(b, scene_);
        b.photons = nullptr;  // the CPU appends per chunk instead
        b.compactPhotons = nullptr;
        b.photonKeys = nullptr;
        b.cellCounts = nullptr;
        b.cellStart = cellStart_.data();
        b.counters = nullptr;
        b.hitPoints = hitPoints_.data();
        b.frameRadiance = frame_.data();
        b.accumulation = accumulation_.data();
    }

    // Photon paths in fixed chunks, each appending to its own lists; the lists are then joined in
    // chunk order, so the maps come out the same for any number of threads.
    void tracePhotons() {
        std::uint32_t paths = bindings_.params.globalPaths + bindings_.params.causticPaths;
        std::size_t chunks = (paths + kPhotonChunk - 1) / kPhotonChunk;
        for (auto& perChunk : chunkPhotons_) {
            perChunk.resize(chunks);
        }
        const Bindings& b = bindings_;
        parallelFor(chunks, 1, [&](std::size_t first, std::size_t last) {
            for (std::size_t c = first; c < last; ++c) {
                std::vector<Photon>& global = chunkPhotons_[MAP_GLOBAL][c];
                std::vector<Photon>& caustic = chunkPhotons_[MAP_CAUSTIC][c];
                global.clear();
                caustic.clear();
                std::uint32_t end = static_cast<std::uint32_t>(std::min<std::size_t>((c + 1) * kPhotonChunk, paths));
                for (std::uint32_t i = static_cast<std::uint32_t>(c * kPhotonChunk); i < end; ++i) {
                    PhotonPath path = startPhotonPath(b, i);
                    while (photonPathAlive(path)) {
                        Photon p;
                        std::uint32_t store = photonBounce(b, path, p);
                        if (store & STORE_GLOBAL) {
                            global.push_back(p);
                        }
                        if (store & STORE_CAUSTIC) {
                            caustic.push_back(p);
                        }
                    }
                }
            }
        });
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            traced_[m].clear();
            for (const std::vector<Photon>& list : chunkPhotons_[m]) {
                traced_[m].insert(traced_[m].end(), list.begin(), list.end());
            }
        }
    }

    // Counting sort of each map by cell key: count, exclusive prefix sum, stable scatter.
    void buildGrid() {
        std::size_t total = traced_[MAP_GLOBAL].size() + traced_[MAP_CAUSTIC].size();
        sorted_.resize(total);
        std::uint32_t offset = 0;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            GridParams& g = bindings_.params.grids[m];
            g.photonOffset = offset;
            g.photonCapacity = static_cast<std::uint32_t>(traced_[m].size());
            const std::vector<Photon>& photons = traced_[m];
            keys_.resize(photons.size());
            parallelFor(photons.size(), 16384, [&](std::size_t first, std::size_t last) {
                for (std::size_t i = first; i < last; ++i) {
                    keys_[i] = photonCellKey(photons[i].position, g);
                }
            });
            std::uint32_t* start = cellStart_.data() + g.cellOffset;
            std::fill(start, start + g.cellCount + 1, 0u);
            for (std::uint32_t key : keys_) {
                start[key] += 1;
            }
            std::uint32_t sum = 0;
            for (std::uint32_t c = 0; c <= g.cellCount; ++c) {
                std::uint32_t n = start[c];
                start[c] = sum;
                sum += n;
            }
            cursor_.assign(start, start + g.cellCount);
            for (std::size_t i = 0; i < photons.size(); ++i) {
                sorted_[offset + cursor_[keys_[i]]++] = photons[i];
            }
            offset += static_cast<std::uint32_t>(photons.size());
        }
        bindings_.sortedPhotons = sorted_.data();
    }

    template <typename PixelFn>
    void forEachPixel(const PixelFn& fn) {
        parallelFor(std::size_t(width_) * height_, kPixelChunk, [&](std::size_t first, std::size_t last) {
            for (std::size_t p = first; p < last; ++p) {
                fn(static_cast<std::uint32_t>(p));
            }
        });
    }

    void tracePixels() {
        const Bindings& b = bindings_;
        forEachPixel([&](std::uint32_t p) { hitPoints_[p] = tracePixel(b, p); });
    }

    void gather() {
        const Bindings& b = bindings_;
        forEachPixel([&](std::uint32_t p) { frame_[p] = glm::vec4(gatherPixel(b, p), 1.0f); });
    }

    void accumulate() {
        std::uint32_t n = bindings_.params.accumulated;
        forEachPixel([&](std::uint32_t p) { accumulation_[p] = accumulateMean(accumulation_[p], frame_[p], n); });
    }

    Image toImage(const std::vector<glm::vec4>& pixels) const {
        Image image(width_, height_);
        image.pixels = pixels;
        return image;
    }

    Scene scene_;
    Bindings bindings_{};
    std::uint32_t width_ = 0;
    std::uint32_t height_ = 0;
    std::vector<std::vector<Photon>> chunkPhotons_[MAP_COUNT];
    std::vector<Photon> traced_[MAP_COUNT];  // each map's photons in path order
    std::vector<std::uint32_t> keys_;
    std::vector<std::uint32_t> cursor_;
    std::vector<Photon> sorted_;             // both maps, each ordered by cell
    std::vector<std::uint32_t> cellStart_;
    std::vector<HitPoint> hitPoints_;
    std::vector<glm::vec4> frame_;
    std::vector<glm::vec4> accumulation_;
};

}  // namespace

std::unique_ptr<Backend> createCpuBackend() { return std::make_unique<CpuBackend>(); }

}  // namespace photon
