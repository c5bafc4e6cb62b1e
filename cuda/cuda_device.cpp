#include "cuda_device.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "cell_scan.h"
#include "cuda_check.h"
#include "device_memory.h"
#include "shared/medium.h"
#include "shared/photon_map.h"

namespace photon {
namespace {

// Stage boundaries timed with CUDA events: the frame's start, then the end of each stage.
constexpr std::uint32_t kMarkCount = STAGE_COUNT + 1;

class CudaDevice final : public Device {
public:
    explicit CudaDevice(const DeviceOptions& options) : kernels_(options.parity ? &kParityKernels : &kFastKernels) {
        int count = cudaDeviceCount();
        if (count == 0) {
            throw RuntimeError("CUDA: no CUDA device is available on this machine");
        }
        int index = 0;
        if (!options.device.empty()) {
            std::size_t used = 0;
            try {
                index = std::stoi(options.device, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != options.device.size()) {
                throw InputError("--device '" + options.device + "': the CUDA backend takes a device index");
            }
            if (index < 0 || index >= count) {
                throw InputError("--device " + options.device + ": there are " + std::to_string(count) +
                                 " CUDA devices (0 to " + std::to_string(count - 1) + ")");
            }
        }
        index_ = index;
        CUDA_CHECK(cudaSetDevice(index), "setup");
        CUDA_CHECK(cudaGetDeviceProperties(&properties_, index), "setup");
        CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "setup");
        for (cudaEvent_t& e : events_) {
            CUDA_CHECK(cudaEventCreate(&e), "setup");
        }
        config_.gridBlocks = static_cast<std::uint32_t>(properties_.multiProcessorCount) * 8u;
        parity_ = options.parity;
        counters_.resize(COUNTER_COUNT, "setup");
    }

    ~CudaDevice() override {
        use();
        cudaStreamSynchronize(stream_);
        for (cudaEvent_t e : events_) {
            cudaEventDestroy(e);
        }
        cudaStreamDestroy(stream_);
    }

    std::string name() const override { return "cuda"; }
    std::string deviceName() const override { return std::string(properties_.name) + (parity_ ? " (parity build)" : ""); }

    void setLaunchConfig(const LaunchConfig& config) { config_ = config; }
    const LaunchConfig& launchConfig() const { return config_; }

    MemoryLimits memoryLimits() override {
        use();
        std::size_t freeBytes = 0;
        std::size_t totalBytes = 0;
        CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes), "memory check");
        std::uint64_t held = 0;
        for (const DeviceArray<unsigned char>& b : buffers_) {
            held += b.bytes();
        }
        MemoryLimits limits;
        limits.device = properties_.name;
        limits.memory = "free device memory";
        limits.total = freeBytes + held;
        return limits;
    }

    // The scan's storage.
    void adjustPlan(BufferPlan& plan, const PhotonBudget&) override { plan.scratchBytes = 64u << 20; }

    void uploadScene(const Scene& scene, const BufferPlan& plan) override {
        use();
        forEachSceneBuffer(scene, plan, [&](std::uint32_t binding, const void* data, std::uint64_t bytes) {
            DeviceArray<unsigned char>& buffer = buffers_[binding];
            buffer.resize(bytes, "upload scene");
            CUDA_CHECK(cudaMemcpy(buffer.data(), data, bytes, cudaMemcpyHostToDevice), "upload scene");
        });
    }

    void allocate(const BufferPlan& plan, const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) override {
        use();
        resizeChangedBuffers(
            plan, [&](std::uint32_t binding, std::uint64_t bytes) { return buffers_[binding].bytes() == bytes; },
            [&](std::uint32_t binding, std::uint64_t bytes) {
                DeviceArray<unsigned char>& buffer = buffers_[binding];
                if (bytes == 0) {
                    buffer.resize(0, "allocate");
                    return;
                }
                buffer.resize(bytes, bufferInfo(binding).name);
                CUDA_CHECK(cudaMemset(buffer.data(), 0, buffer.bytes()), bufferInfo(binding).name);
            });
        scan_.reserve(budget.largestCells() + 1);
        width_ = width;
        height_ = height;
        hostPixels_.resize(std::size_t(width) * height, "allocate image");
    }

    // One stream: each stage's kernels, then an event at its end.
    void beginStages(const FrameParams& params, bool resume) override {
        use();
        bind(params);
        CUDA_CHECK(cudaEventRecord(events_[0], stream_), "frame start");
        if (!resume) {
            CUDA_CHECK(cudaMemsetAsync(bindings_.counters, 0, COUNTER_COUNT * sizeof(std::uint32_t), stream_),
                       "frame start");
        }
    }

    void runStage(std::uint32_t stage, const FrameParams& params) override {
        use();
        // The fast build's scenes without media take the kernels compiled without them.
        const StageKernels* kernels = kernels_ == &kFastKernels && !sceneHasMedia(params) ? &kFastNoMediaKernels : kernels_;
        if (StageLaunch launch = kernels->stage[stage]) {
            launch(bindings_, config_, stream_);
        } else if (stage == STAGE_BUILD_GRID) {
            buildGrid(params);
        } else {
            throw std::logic_error(std::string("CUDA: no kernels for stage ") + kStages[stage].name);
        }
        CUDA_CHECK(cudaEventRecord(events_[stage + 1], stream_), kStages[stage].name);
    }

    void skipStage(std::uint32_t stage) override {
        use();
        CUDA_CHECK(cudaEventRecord(events_[stage + 1], stream_), kStages[stage].name);
    }

    FrameResult endStages() override {
        use();
        readCounters();
        FrameResult result;
        for (std::uint32_t i = 0; i < STAGE_COUNT; ++i) {
            float ms = 0.0f;
            CUDA_CHECK(cudaEventElapsedTime(&ms, events_[i], events_[i + 1]), "timing");
            result.ms[i] = ms;
        }
        std::copy(counters_.data(), counters_.data() + COUNTER_COUNT, result.counters);
        return result;
    }

    // One copy into pinned memory, then into the caller's (or, to measure the difference,
    // straight into the caller's pageable memory).
    void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) override {
        use();
        const unsigned char* source = buffers_[binding].data() + offset;
        bool pixels = binding != BINDING_PARAMS && bufferInfo(binding).size == BUFFER_PER_PIXEL;
        if (!pixels || !config_.pinnedReadback || bytes > hostPixels_.bytes()) {
            CUDA_CHECK(cudaMemcpy(data, source, bytes, cudaMemcpyDeviceToHost), "readback");
            return;
        }
        CUDA_CHECK(cudaMemcpyAsync(hostPixels_.data(), source, bytes, cudaMemcpyDeviceToHost, stream_), "readback");
        CUDA_CHECK(cudaStreamSynchronize(stream_), "readback");
        std::copy_n(reinterpret_cast<const unsigned char*>(hostPixels_.data()), bytes, static_cast<unsigned char*>(data));
    }

    void writeBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, const void* data) override {
        use();
        CUDA_CHECK(cudaStreamSynchronize(stream_), "write");
        CUDA_CHECK(cudaMemcpy(buffers_[binding].data() + offset, data, bytes, cudaMemcpyHostToDevice), "write");
    }

    PrimaryRayTiming timePrimaryRays(int repeats) {
        if (width_ == 0) {
            throw std::logic_error("timePrimaryRays before a frame");
        }
        DeviceArray<std::uint32_t> hits;
        hits.resize(1, "primary rays");
        std::vector<double> ms;
        std::uint32_t hitCount = 0;
        for (int r = -1; r < repeats; ++r) {  // r = -1: the warm-up
            CUDA_CHECK(cudaMemsetAsync(hits.data(), 0, sizeof(std::uint32_t), stream_), "primary rays");
            CUDA_CHECK(cudaEventRecord(events_[0], stream_), "primary rays");
            kernels_->tracePrimaryRays(bindings_, hits.data(), config_, stream_);
            CUDA_CHECK(cudaEventRecord(events_[1], stream_), "primary rays");
            CUDA_CHECK(cudaMemcpyAsync(&hitCount, hits.data(), sizeof(hitCount), cudaMemcpyDeviceToHost, stream_),
                       "primary rays");
            CUDA_CHECK(cudaStreamSynchronize(stream_), "primary rays");
            float t = 0.0f;
            CUDA_CHECK(cudaEventElapsedTime(&t, events_[0], events_[1]), "primary rays");
            if (r >= 0) {
                ms.push_back(t);
            }
        }
        std::sort(ms.begin(), ms.end());
        PrimaryRayTiming timing;
        timing.medianMs = ms.empty() ? 0.0 : ms[ms.size() / 2];
        timing.rays = std::uint64_t(width_) * height_;
        timing.hits = hitCount;
        return timing;
    }

private:
    // The maps' photons into cell order: count, CUB's scan of each map's cells, then the scatter,
    // or with deterministic maps the scatter and each cell put in canonical order.
    void buildGrid(const FrameParams& params) {
        const Bindings& b = bindings_;
        const StageKernels& kernels = *kernels_;
        kernels.countCells(b, config_, stream_);
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& g = params.grids[m];
            if (g.photonCapacity != 0) {
                scan_.exclusiveSum(b.cellCounts + g.cellOffset, b.cellStart + g.cellOffset, g.cellCount + 1, stream_);
            }
        }
        if ((params.flags & FLAG_DETERMINISTIC) != 0u) {
            kernels.orderPhotons(b, config_, stream_);
        } else {
            kernels.scatterPhotons(b, config_, stream_);
        }
    }

    void bind(const FrameParams& params) {
        void* pointers[BINDING_COUNT] = {};
        for (const BufferInfo& info : kBuffers) {
            pointers[info.binding] = buffers_[info.binding].data();
        }
        pointBindings(bindings_, pointers);
        bindings_.params = params;
    }

    // The counters of the frame so far, into host memory.
    void readCounters() {
        CUDA_CHECK(cudaMemcpyAsync(counters_.data(), bindings_.counters, counters_.bytes(), cudaMemcpyDeviceToHost, stream_),
                   "counters");
        CUDA_CHECK(cudaStreamSynchronize(stream_), "frame");
    }

    // This device's GPU for the calls that follow: several CudaDevices in one process (one per
    // GPU) take turns on the host thread.
    void use() const { cudaSetDevice(index_); }

    int index_ = 0;
    const StageKernels* kernels_;  // fast or parity
    bool parity_ = false;
    cudaDeviceProp properties_{};
    cudaStream_t stream_ = nullptr;
    cudaEvent_t events_[kMarkCount] = {};
    LaunchConfig config_;
    Bindings bindings_{};
    std::uint32_t width_ = 0;
    std::uint32_t height_ = 0;

    DeviceArray<unsigned char> buffers_[BINDING_COUNT];  // by binding (shared/bindings.h)
    CellScan scan_;
    PinnedArray<std::uint32_t> counters_;                // the last frame's counters
    PinnedArray<glm::vec4> hostPixels_;                  // image readbacks
};

}  // namespace

int cudaDeviceCount() {
    int count = 0;
    if (cudaGetDeviceCount(&count) != cudaSuccess) {
        cudaGetLastError();  // clear the sticky "no device" error
        return 0;
    }
    return count;
}

std::unique_ptr<Device> createCudaDevice(const DeviceOptions& options) {
    return std::make_unique<CudaDevice>(options);
}

PrimaryRayTiming timeCudaPrimaryRays(Device& device, int repeats) {
    auto* cuda = dynamic_cast<CudaDevice*>(&device);
    return cuda ? cuda->timePrimaryRays(repeats) : PrimaryRayTiming{};
}

LaunchConfig cudaLaunchConfig(Device& device) {
    auto* cuda = dynamic_cast<CudaDevice*>(&device);
    return cuda ? cuda->launchConfig() : LaunchConfig{};
}

void setCudaLaunchConfig(Device& device, const LaunchConfig& config) {
    if (auto* cuda = dynamic_cast<CudaDevice*>(&device)) {
        cuda->setLaunchConfig(config);
    }
}

}  // namespace photon
