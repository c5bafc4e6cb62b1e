#include "cuda_backend.h"

#include <algorithm>
#include <string>
#include <vector>

#include "cell_scan.h"
#include "cell_sort.h"
#include "cuda_check.h"
#include "device_memory.h"

namespace photon {
namespace {

// Stage boundaries timed with CUDA events.
enum Mark { kStart, kPhotonsTraced, kGridBuilt, kPixelsTraced, kGathered, kAccumulated, kMarkCount };

template <typename T>
void upload(DeviceArray<T>& device, const std::vector<T>& host, const char* what) {
    device.resize(std::max<std::size_t>(host.size(), 1), what);
    if (!host.empty()) {
        CUDA_CHECK(cudaMemcpy(device.data(), host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice), what);
    }
}

class CudaBackend final : public Backend {
public:
    explicit CudaBackend(const BackendOptions& options) : kernels_(options.parity ? &kParityKernels : &kFastKernels) {
        int count = cudaDeviceCount();
        if (count == 0) {
            throw RuntimeError("CUDA: no CUDA device is available on this machine");
        }
        int index = 0;
        if (!options.device.empty()) {
            try {
                index = std::stoi(options.device);
            } catch (const std::exception&) {
                throw InputError("--device '" + options.device + "': the CUDA backend takes a device index");
            }
            if (index < 0 || index >= count) {
                throw InputError("--device " + options.device + ": there are " + std::to_string(count) + " CUDA devices");
            }
        }
        CUDA_CHECK(cudaSetDevice(index), "setup");
        CUDA_CHECK(cudaGetDeviceProperties(&properties_, index), "setup");
        CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking), "setup");
        for (cudaEvent_t& e : events_) {
            CUDA_CHECK(cudaEventCreate(&e), "setup");
        }
        config_.gridBlocks = static_cast<std::uint32_t>(properties_.multiProcessorCount) * 8u;
        parity_ = options.parity;
    }

    ~CudaBackend() override {
        for (cudaEvent_t e : events_) {
            cudaEventDestroy(e);
        }
        cudaStreamDestroy(stream_);
    }

    std::string name() const override { return "cuda"; }
    std::string deviceName() const override { return std::string(properties_.name) + (parity_ ? " (parity build)" : ""); }

    void setLaunchConfig(const LaunchConfig& config) {
        if (config.compactPhotons && std::any_of(scene().materials.begin(), scene().materials.end(),
                                                 [](const Material& m) { return m.type == MATERIAL_GLOSSY; })) {
            throw InputError("compact photons carry no direction: the scene's glossy materials need it");
        }
        config_ = config;
    }

    PhotonMaps readPhotonMaps() override {
        PhotonMaps maps;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& g = bindings_.params.grids[m];
            std::uint32_t n = std::min(counters_[COUNTER_STORED_GLOBAL + m], g.photonCapacity);
            maps.photons[m].resize(n);
            maps.cellStart[m].resize(std::size_t(g.cellCount) + 1);
            if (n > 0) {
                CUDA_CHECK(cudaMemcpy(maps.photons[m].data(), sortedPhotons_.data() + g.photonOffset, n * sizeof(Photon),
                                      cudaMemcpyDeviceToHost),
                           "readback");
            }
            CUDA_CHECK(cudaMemcpy(maps.cellStart[m].data(), cellStart_.data() + g.cellOffset,
                                  maps.cellStart[m].size() * sizeof(std::uint32_t), cudaMemcpyDeviceToHost),
                       "readback");
        }
        return maps;
    }

    std::vector<HitPoint> readHitPoints() override {
        std::vector<HitPoint> hits(hitPoints_.size());
        CUDA_CHECK(cudaMemcpy(hits.data(), hitPoints_.data(), hitPoints_.bytes(), cudaMemcpyDeviceToHost), "readback");
        return hits;
    }

    Image readFrame() override { return readPixels(frameRadiance_); }

protected:
    void uploadScene(const Scene& scene) override {
        upload(spheres_, scene.spheres, "upload scene");
        upload(planes_, scene.planes, "upload scene");
        upload(quads_, scene.quads, "upload scene");
        upload(triangles_, scene.triangles, "upload scene");
        upload(materials_, scene.materials, "upload scene");
        upload(lights_, scene.lights, "upload scene");
        upload(targets_, scene.targets, "upload scene");
    }

    void allocate(const PhotonBudget& budget, std::uint32_t width, std::uint32_t height) override {
        std::size_t pixels = std::size_t(width) * height;
        std::size_t photons = std::max<std::size_t>(budget.totalCapacity(), 1);
        std::size_t cells = budget.totalCellEntries();
        std::size_t need = photons * (2 * sizeof(Photon) + sizeof(CompactPhoton) + sizeof(std::uint32_t)) +
                           2 * cells * sizeof(std::uint32_t) +
                           pixels * (sizeof(HitPoint) + 2 * sizeof(glm::vec4));
        // Free the old buffers first, then check what the device has: too much fails here, before work.
        for (DeviceArray<Photon>* a : {&photons_, &sortedPhotons_}) {
            a->resize(0, "allocate");
        }
        compactPhotons_.resize(0, "allocate");
        photonKeys_.resize(0, "allocate");
        std::size_t freeBytes = 0;
        std::size_t totalBytes = 0;
        CUDA_CHECK(cudaMemGetInfo(&freeBytes, &totalBytes), "allocate");
        if (need > freeBytes) {
            throw InputError("CUDA: " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                             std::to_string(budget.totalPaths()) + " photons per frame needs " +
                             std::to_string(need >> 20) + " MiB of device memory, " + properties_.name + " has " +
                             std::to_string(freeBytes >> 20) + " MiB free: lower --photons or the resolution");
        }
        photons_.resize(photons, "allocate photons");
        sortedPhotons_.resize(photons, "allocate photons");
        compactPhotons_.resize(photons, "allocate photons");
        photonKeys_.resize(photons, "allocate photons");
        cellCounts_.resize(cells, "allocate grid");
        cellStart_.resize(cells, "allocate grid");
        CUDA_CHECK(cudaMemset(cellCounts_.data(), 0, cellCounts_.bytes()), "allocate grid");
        CUDA_CHECK(cudaMemset(cellStart_.data(), 0, cellStart_.bytes()), "allocate grid");
        scan_.reserve(std::max(budget.cells[MAP_GLOBAL], budget.cells[MAP_CAUSTIC]) + 1);
        counters_.resize(COUNTER_COUNT, "allocate");
        deviceCounters_.resize(COUNTER_COUNT, "allocate");
        hitPoints_.resize(pixels, "allocate image");
        frameRadiance_.resize(pixels, "allocate image");
        accumulation_.resize(pixels, "allocate image");
        hostPixels_.resize(pixels, "allocate image");
        CUDA_CHECK(cudaMemset(counters_.data(), 0, counters_.bytes()), "allocate");
        width_ = width;
        height_ = height;
    }

    FrameStats runFrame(const FrameParams& params) override {
        bind(params);
        const Bindings& b = bindings_;
        const StageKernels& kernels = config_.compactPhotons ? kCompactKernels : *kernels_;
        CUDA_CHECK(cudaEventRecord(events_[kStart], stream_), "tracePhotons");
        CUDA_CHECK(cudaMemsetAsync(deviceCounters_.data(), 0, deviceCounters_.bytes(), stream_), "tracePhotons");
        kernels.tracePhotons(b, params.globalPaths + params.causticPaths, config_, stream_);
        CUDA_CHECK(cudaEventRecord(events_[kPhotonsTraced], stream_), "tracePhotons");

        if (config_.radixSortGrid) {
            // CUB's sort takes its item count on the host: this variant waits for the photon pass.
            CUDA_CHECK(cudaMemcpyAsync(counters_.data(), deviceCounters_.data(), counters_.bytes(),
                                       cudaMemcpyDeviceToHost, stream_),
                       "buildGrid (sort)");
            CUDA_CHECK(cudaStreamSynchronize(stream_), "buildGrid (sort)");
        }
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            const GridParams& g = params.grids[m];
            if (g.photonCapacity == 0) {
                continue;
            }
            kernels.countCells(b, m, config_, stream_);
            scan_.exclusiveSum(cellCounts_.data() + g.cellOffset, cellStart_.data() + g.cellOffset, g.cellCount + 1, stream_);
            if (config_.radixSortGrid) {
                std::uint32_t n = std::min(counters_[COUNTER_STORED_GLOBAL + m], g.photonCapacity);
                int bits = 1;
                while ((1ull << bits) < g.cellCount) {
                    bits += 1;
                }
                sort_.reserve(g.photonCapacity);
                sort_.sort(photonKeys_.data() + g.photonOffset, photons_.data() + g.photonOffset,
                           sortedPhotons_.data() + g.photonOffset, n, bits, stream_);
                CUDA_CHECK(cudaMemsetAsync(cellCounts_.data() + g.cellOffset, 0, (g.cellCount + 1) * sizeof(std::uint32_t),
                                           stream_),
                           "buildGrid (sort)");
            } else {
                kernels.scatterPhotons(b, m, config_, stream_);
            }
        }
        CUDA_CHECK(cudaEventRecord(events_[kGridBuilt], stream_), "buildGrid");

        kernels.tracePixels(b, config_, stream_);
        CUDA_CHECK(cudaEventRecord(events_[kPixelsTraced], stream_), "tracePixels");
        kernels.gather(b, config_, stream_);
        CUDA_CHECK(cudaEventRecord(events_[kGathered], stream_), "gather");
        kernels.accumulate(b, config_, stream_);
        CUDA_CHECK(cudaEventRecord(events_[kAccumulated], stream_), "accumulate");
        CUDA_CHECK(cudaMemcpyAsync(counters_.data(), deviceCounters_.data(), counters_.bytes(), cudaMemcpyDeviceToHost,
                                   stream_),
                   "accumulate");
        CUDA_CHECK(cudaEventSynchronize(events_[kAccumulated]), "frame");
        CUDA_CHECK(cudaStreamSynchronize(stream_), "frame");

        FrameStats stats;
        double* stage[] = {&stats.ms.tracePhotons, &stats.ms.buildGrid, &stats.ms.tracePixels, &stats.ms.gather,
                           &stats.ms.accumulate};
        for (int i = 0; i < kMarkCount - 1; ++i) {
            float ms = 0.0f;
            CUDA_CHECK(cudaEventElapsedTime(&ms, events_[i], events_[i + 1]), "timing");
            *stage[i] = ms;
        }
        stats.emitted[MAP_GLOBAL] = params.globalPaths;
        stats.emitted[MAP_CAUSTIC] = params.causticPaths;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            stats.stored[m] = counters_[COUNTER_STORED_GLOBAL + m];
            stats.capacity[m] = params.grids[m].photonCapacity;
        }
        return stats;
    }

    Image readAccumulation() override { return readPixels(accumulation_); }

private:
    void bind(const FrameParams& params) {
        Bindings& b = bindings_;
        b.params = params;
        b.spheres = spheres_.data();
        b.planes = planes_.data();
        b.quads = quads_.data();
        b.triangles = triangles_.data();
        b.materials = materials_.data();
        b.lights = lights_.data();
        b.targets = targets_.data();
        b.photons = photons_.data();
        b.photonKeys = photonKeys_.data();
        b.sortedPhotons = sortedPhotons_.data();
        b.compactPhotons = compactPhotons_.data();
        b.cellCounts = cellCounts_.data();
        b.cellStart = cellStart_.data();
        b.counters = deviceCounters_.data();
        b.hitPoints = hitPoints_.data();
        b.frameRadiance = frameRadiance_.data();
        b.accumulation = accumulation_.data();
    }

    // One copy into pinned memory, then into the image (or, to measure the difference, straight
    // into the image's pageable memory).
    Image readPixels(const DeviceArray<glm::vec4>& pixels) {
        Image image(width_, height_);
        if (!config_.pinnedReadback) {
            CUDA_CHECK(cudaMemcpy(image.pixels.data(), pixels.data(), pixels.bytes(), cudaMemcpyDeviceToHost), "readback");
            return image;
        }
        CUDA_CHECK(cudaMemcpyAsync(hostPixels_.data(), pixels.data(), pixels.bytes(), cudaMemcpyDeviceToHost, stream_),
                   "readback");
        CUDA_CHECK(cudaStreamSynchronize(stream_), "readback");
        std::copy(hostPixels_.data(), hostPixels_.data() + hostPixels_.size(), image.pixels.begin());
        return image;
    }

    const StageKernels* kernels_;  // fast or parity
    bool parity_ = false;
    cudaDeviceProp properties_{};
    cudaStream_t stream_ = nullptr;
    cudaEvent_t events_[kMarkCount] = {};
    LaunchConfig config_;
    Bindings bindings_{};
    std::uint32_t width_ = 0;
    std::uint32_t height_ = 0;

    // Scene.
    DeviceArray<Sphere> spheres_;
    DeviceArray<Plane> planes_;
    DeviceArray<Quad> quads_;
    DeviceArray<Triangle> triangles_;
    DeviceArray<Material> materials_;
    DeviceArray<Light> lights_;
    DeviceArray<CausticTarget> targets_;
    // Photon maps: both maps side by side, see PhotonBudget.
    DeviceArray<Photon> photons_;        // in the order they were stored
    DeviceArray<std::uint32_t> photonKeys_;
    DeviceArray<Photon> sortedPhotons_;  // in cell order
    DeviceArray<CompactPhoton> compactPhotons_;  // the same, 16 bytes each (LaunchConfig::compactPhotons)
    DeviceArray<std::uint32_t> cellCounts_;
    DeviceArray<std::uint32_t> cellStart_;
    CellScan scan_;
    CellSort sort_;  // LaunchConfig::radixSortGrid only
    DeviceArray<std::uint32_t> deviceCounters_;
    PinnedArray<std::uint32_t> counters_;  // last frame's counters
    // Image.
    DeviceArray<HitPoint> hitPoints_;
    DeviceArray<glm::vec4> frameRadiance_;
    DeviceArray<glm::vec4> accumulation_;
    PinnedArray<glm::vec4> hostPixels_;
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

std::unique_ptr<Backend> createCudaBackend(const BackendOptions& options) {
    return std::make_unique<CudaBackend>(options);
}

void setCudaLaunchConfig(Backend& backend, const LaunchConfig& config) {
    if (auto* cuda = dynamic_cast<CudaBackend*>(&backend)) {
        cuda->setLaunchConfig(config);
    }
}

}  // namespace photon
