#include "cpu_device.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <vector>

#include "core/system/parallel.h"
#include "core/system/host_memory.h"
#include "shared/denoise.h"
#include "shared/reproject.h"
#include "shared/eye_trace.h"
#include "shared/photon_map.h"
#include "shared/photon_trace.h"
#include "shared/progressive.h"
#include "shared/sppm.h"

namespace photon {
namespace {

constexpr std::size_t kPhotonChunk = 2048;  // photon paths per chunk of the photon pass
constexpr std::size_t kPixelChunk = 256;
constexpr std::size_t kGridChunk = 16384;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::uint64_t paddedBytes(std::uint64_t bytes) { return (bytes + 15) / 16 * 16; }

// The device's buffers: one 16-byte aligned array per binding, zeroed when sized, whose pages
// cost nothing until a stage writes them (core/system/host_memory.h).
class HostBuffers {
public:
    void resize(std::uint32_t binding, std::uint64_t bytes) {
        storage_[binding] = ZeroedMemory();  // before the new one: peak memory is the larger of the two
        storage_[binding] = ZeroedMemory(paddedBytes(bytes));
    }
    void* data(std::uint32_t binding) { return storage_[binding].data(); }
    std::uint64_t bytes(std::uint32_t binding) const { return storage_[binding].bytes(); }
    std::uint64_t total() const {
        std::uint64_t sum = 0;
        for (const ZeroedMemory& s : storage_) {
            sum += s.bytes();
        }
        return sum;
    }

private:
    ZeroedMemory storage_[BINDING_COUNT];
};

class CpuDevice final : public Device {
public:
    std::string name() const override { return "cpu"; }

    std::string deviceName() const override { return "CPU (" + std::to_string(workerThreads()) + " threads)"; }
    bool buffersInHostMemory() const override { return true; }
    bool runsOnCpu() const override { return true; }

    MemoryLimits memoryLimits() override {
        MemoryLimits limits;
        limits.device = "this machine";
        limits.memory = "memory this process may use";
        limits.total = availableHostMemory() + buffers_.total();
        return limits;
    }

    // The readback of the image and its encoding live beside the buffers. The GPUs' ordering
    // arrays go unused: this device sorts each cell (buildGrid).
    void adjustPlan(BufferPlan& plan, const PhotonBudget&) override {
        plan.scratchBytes = plan.elements[BINDING_ACCUMULATION] * kHostBytesPerPixel;
        plan.elements[BINDING_PHOTON_ORDER] = 1;
    }

    // The scene stays where the Renderer keeps it; the stages read its arrays in place.
    void uploadScene(const Scene& scene, const BufferPlan&) override { scene_ = &scene; }

    void allocate(const BufferPlan& plan, const PhotonBudget&, std::uint32_t width, std::uint32_t height) override {
        resizeChangedBuffers(
            plan, [&](std::uint32_t binding, std::uint64_t bytes) { return buffers_.bytes(binding) == paddedBytes(bytes); },
            [&](std::uint32_t binding, std::uint64_t bytes) { buffers_.resize(binding, bytes); });
        pixels_ = std::size_t(width) * height;
    }

    void beginStages(const FrameParams& params, bool resume) override {
        bind(params, resume);
        result_ = FrameResult{};
    }

    // Each stage by its function below, timed on the host's steady clock.
    void runStage(std::uint32_t stage, const FrameParams&) override {
#define PH_CPU_STAGE(NAME, id, name, label) &CpuDevice::name,
        static constexpr void (CpuDevice::*kRun[])() = {PH_STAGES(PH_CPU_STAGE)};
        auto t = std::chrono::steady_clock::now();
        (this->*kRun[stage])();
        result_.ms[stage] = millisecondsSince(t);
    }

    FrameResult endStages() override {
        std::copy(bindings_.counters, bindings_.counters + COUNTER_COUNT, result_.counters);
        return result_;
    }

    void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) override {
        const void* source = binding >= 1 && bufferInfo(binding).size == BUFFER_PER_SCENE
                                 ? sceneArray(*scene_, binding).data
                                 : buffers_.data(binding);
        std::memcpy(data, static_cast<const char*>(source) + offset, bytes);
    }

    void writeBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, const void* data) override {
        std::memcpy(static_cast<char*>(buffers_.data(binding)) + offset, data, bytes);
    }

private:
    void bind(const FrameParams& params, bool resume) {
        void* pointers[BINDING_COUNT] = {};
        for (const BufferInfo& info : kBuffers) {
            pointers[info.binding] = buffers_.data(info.binding);
        }
        pointBindings(bindings_, pointers);
        bindSceneArrays(bindings_, *scene_);
        bindings_.params = params;
        if (!resume) {
            std::fill(bindings_.counters, bindings_.counters + COUNTER_COUNT, 0u);
        }
    }

    void tracePhotons() {
        parallelFor(bindings_.params.pathCount, kPhotonChunk, [&](std::size_t first, std::size_t last) {
            for (std::size_t i = first; i < last; ++i) {
                traceSharedPhotonPath(bindings_, static_cast<std::uint32_t>(i));
            }
        });
    }

    // The counting sort of photon_map.h, then each cell in canonical order: by photon id. A sort
    // of each cell, not the GPUs' rank and merge steps: on two cores those cost 60-70 ms more a
    // frame at 1M photons (the rank step's n·ORDER_CHUNK compares in a caustic focus).
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
            // The scatter's places hold (id, photon) pairs, each cell's then put in id order: the
            // canonical order.
            order_.resize(stored);
            const Photon* photons = b.photons + g.photonOffset;
            parallelFor(stored, kGridChunk, [&](std::size_t first, std::size_t last) {
                for (std::size_t i = first; i < last; ++i) {
                    order_[cellPlace(b, m, static_cast<std::uint32_t>(i))] = (std::uint64_t(photons[i].id) << 32) | i;
                }
            });
            const std::uint32_t* start = b.cellStart + g.cellOffset;
            parallelFor(g.cellCount, kGridChunk, [&](std::size_t first, std::size_t last) {
                for (std::size_t c = first; c < last; ++c) {
                    std::sort(order_.begin() + start[c], order_.begin() + start[c + 1]);
                }
            });
            parallelFor(stored, kGridChunk, [&](std::size_t first, std::size_t last) {
                for (std::size_t place = first; place < last; ++place) {
                    placePhoton(b, m, static_cast<std::uint32_t>(place), static_cast<std::uint32_t>(order_[place]));
                }
            });
        }
    }

    void tracePixels() {
        forEachPixel([&](std::uint32_t p) { bindings_.hitPoints[p] = tracePixel(bindings_, p); });
    }

    void reproject() {
        if ((bindings_.params.flags & FLAG_REPROJECT) == 0u) {
            return;
        }
        for (std::uint32_t pass = 0; pass < REPROJECT_PASS_COUNT; ++pass) {
            forEachPixel([&](std::uint32_t p) { reprojectPass(bindings_, p, pass); });
        }
    }

    void gather() {
        const FrameParams& params = bindings_.params;
        bool start = sppmStarts(params.estimator, params.view, params.accumulated);
        forEachPixel([&](std::uint32_t p) {
            bindings_.frameRadiance[p] = gatherStage(bindings_, p, params.estimator, params.globalMode, start);
        });
    }

    void accumulate() {
        forEachPixel([&](std::uint32_t p) { accumulateStage(bindings_, p); });
    }

    void denoise() {
        if ((bindings_.params.flags & FLAG_DENOISE) == 0u) {
            return;
        }
        for (std::uint32_t pass = 0; pass < DENOISE_PASS_COUNT; ++pass) {
            forEachPixel([&](std::uint32_t p) { denoisePass(bindings_, p, pass); });
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
    FrameResult result_;  // of the frame in flight
    std::vector<std::uint64_t> order_;  // the grid build's (id, photon) order, for one map
};

}  // namespace

std::unique_ptr<Device> createCpuDevice() { return std::make_unique<CpuDevice>(); }

}  // namespace photon
