#include "cpu_backend.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <vector>

#include "core/parallel.h"
#include "shared/eye_trace.h"
#include "shared/sppm.h"
#include "shared/photon_map.h"
#include "shared/photon_trace.h"
#include "shared/progressive.h"

namespace photon {
namespace {

constexpr std::size_t kPhotonChunk = 2048;  // photon paths per chunk of the photon pass
constexpr std::size_t kPixelChunk = 256;
constexpr std::size_t kGridChunk = 16384;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::uint64_t paddedBytes(std::uint64_t bytes) { return (bytes + 15) / 16 * 16; }

// The backend's buffers: one 16-byte aligned array per binding, zeroed when sized.
class HostBuffers {
public:
    void resize(std::uint32_t binding, std::uint64_t bytes) {
        storage_[binding].assign(paddedBytes(bytes) / 16, glm::vec4(0.0f));
        storage_[binding].shrink_to_fit();
    }
    void* data(std::uint32_t binding) { return storage_[binding].data(); }
    std::uint64_t bytes(std::uint32_t binding) const { return storage_[binding].size() * sizeof(glm::vec4); }
    std::uint64_t total() const {
        std::uint64_t sum = 0;
        for (const auto& s : storage_) {
            sum += s.size() * sizeof(glm::vec4);
        }
        return sum;
    }

private:
    std::vector<glm::vec4> storage_[BINDING_COUNT];
};

class CpuBackend final : public Backend {
public:
    std::string name() const override { return "cpu"; }

    std::string deviceName() const override { return "CPU (" + std::to_string(workerThreads()) + " threads)"; }

    MemoryLimits memoryLimits() override {
        MemoryLimits limits;
        limits.device = "this machine";
        limits.memory = "memory this process may use";
        limits.total = availableHostMemory() + buffers_.total();
        return limits;
    }

protected:
    // The readback of the image and its encoding live beside the buffers.
    void adjustPlan(BufferPlan& plan, const PhotonBudget&) override {
        plan.scratchBytes = plan.elements[BINDING_ACCUMULATION] * kHostBytesPerPixel;
    }

    // The scene stays where the Backend keeps it; the stages read its arrays in place.
    void uploadScene(const Scene& scene, const BufferPlan&) override { scene_ = &scene; }

    // Buffers whose size is unchanged are kept (a grown photon map keeps the accumulated image);
    // the others are freed before any is allocated, so that old and new need not fit together.
    void allocate(const BufferPlan& plan, const PhotonBudget&, std::uint32_t width, std::uint32_t height) override {
        std::vector<std::uint32_t> changed;
        for (const BufferInfo& info : kBuffers) {
            if (info.size != BUFFER_PER_SCENE && buffers_.bytes(info.binding) != paddedBytes(plan.bytes(info.binding))) {
                changed.push_back(info.binding);
                buffers_.resize(info.binding, 0);
            }
        }
        for (std::uint32_t binding : changed) {
            buffers_.resize(binding, plan.bytes(binding));
        }
        pixels_ = std::size_t(width) * height;
    }

    FrameResult runFrame(const FrameParams& params) override {
        bind(params);
        FrameResult result;
        auto t = std::chrono::steady_clock::now();
        tracePhotons();
        result.ms.tracePhotons = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        buildGrid();
        result.ms.buildGrid = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        forEachPixel([&](std::uint32_t p) { bindings_.hitPoints[p] = tracePixel(bindings_, p); });
        result.ms.tracePixels = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        forEachPixel([&](std::uint32_t p) {
            bindings_.frameRadiance[p] = glm::vec4(gatherStage(bindings_, p, params.estimator, params.globalMode), 1.0f);
        });
        result.ms.gather = millisecondsSince(t);

        t = std::chrono::steady_clock::now();
        forEachPixel([&](std::uint32_t p) { bindings_.accumulation[p] = accumulatePixel(bindings_, p); });
        result.ms.accumulate = millisecondsSince(t);

        std::copy(bindings_.counters, bindings_.counters + COUNTER_COUNT, result.counters);
        return result;
    }

    void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) override {
        const void* source = binding >= 1 && bufferInfo(binding).size == BUFFER_PER_SCENE
                                 ? sceneArray(*scene_, binding).data
                                 : buffers_.data(binding);
        std::memcpy(data, static_cast<const char*>(source) + offset, bytes);
    }

private:
    void bind(const FrameParams& params) {
        void* pointers[BINDING_COUNT] = {};
        for (const BufferInfo& info : kBuffers) {
            pointers[info.binding] = buffers_.data(info.binding);
        }
        pointBindings(bindings_, pointers);
        bindSceneArrays(bindings_, *scene_);
        bindings_.params = params;
        std::fill(bindings_.counters, bindings_.counters + COUNTER_COUNT, 0u);
    }

    void tracePhotons() {
        parallelFor(bindings_.params.pathCount, kPhotonChunk, [&](std::size_t first, std::size_t last) {
            for (std::size_t i = first; i < last; ++i) {
                traceSharedPhotonPath(bindings_, static_cast<std::uint32_t>(i));
            }
        });
    }

    // The counting sort of photon_map.h, then each cell in canonical order: by photon id.
    void buildGrid() {
        const Bindings& b = bindings_;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& g = b.params.grids[m];
            std::uint32_t stored = storedPhotons(b, m);
            parallelFor(stored, kGridChunk, [&](std::size_t first, std::size_t last) {
                for (std::size_t i = first; i < last; ++i) {
                    countPhotonCell(b, m, static_cast<std::uint32_t>(i));
                }
            });
            std::uint32_t sum = 0;
            for (std::uint32_t c = g.cellOffset; c <= g.cellOffset + g.cellCount; ++c) {
                b.cellStart[c] = sum;
                sum += c < g.cellOffset + g.cellCount ? b.cellCounts[c] : 0u;
            }
            parallelFor(stored, kGridChunk, [&](std::size_t first, std::size_t last) {
                for (std::size_t i = first; i < last; ++i) {
                    scatterPhoton(b, m, static_cast<std::uint32_t>(i));
                }
            });
            Photon* photons = b.sortedPhotons + g.photonOffset;
            const std::uint32_t* start = b.cellStart + g.cellOffset;
            parallelFor(g.cellCount, kGridChunk, [&](std::size_t first, std::size_t last) {
                for (std::size_t c = first; c < last; ++c) {
                    std::sort(photons + start[c], photons + start[c + 1],
                              [](const Photon& x, const Photon& y) { return x.id < y.id; });
                }
            });
        }
    }

    template <typename PixelFn>
    void forEachPixel(const PixelFn& fn) {
        parallelFor(pixels_, kPixelChunk, [&](std::size_t first, std::size_t last) {
            for (std::size_t p = first; p < last; ++p) {
                fn(static_cast<std::uint32_t>(p));
            }
        });
    }

    const Scene* scene_ = nullptr;
    HostBuffers buffers_;
    Bindings bindings_{};
    std::size_t pixels_ = 0;
};

}  // namespace

std::unique_ptr<Backend> createCpuBackend() { return std::make_unique<CpuBackend>(); }

}  // namespace photon
