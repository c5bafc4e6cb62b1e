// The one interface every program talks to. A Renderer owns what a render is (scene, settings,
// camera, photon budget, estimator policy, footprints, statistics, the photon maps' growth) and
// runs the one stage list of shared/stages.h over its Devices (core/frame/device.h: CPU, CUDA,
// Vulkan), which only allocate, upload, run a stage and read back. What a frame computes is
// decided here and in shared/; what it needs (core/frame/buffers.h), its statistics and the
// readbacks of its results are worked out here once for all devices.
//
// With several devices, a frame's photon paths are split over them by index range; after the
// photon pass a Collective (core/frame/collective.h) gathers every device's photons into the
// first device's maps, which runs the rest of the frame. The image is the same, bit for bit with
// --deterministic, as one device's.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/frame/buffers.h"
#include "core/frame/collective.h"
#include "core/frame/device.h"
#include "core/frame/estimator_policy.h"
#include "core/frame/footprints.h"
#include "core/frame/frame_setup.h"
#include "core/image/image.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"
#include "shared/layout.h"
#include "shared/stages.h"

namespace photon {

// The photon maps as reports name them, by map id (shared/constants.h's rows).
#define PH_MAP_NAME(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) name,
inline constexpr const char* kMapNames[] = {PH_MAPS(PH_MAP_NAME)};
#undef PH_MAP_NAME
static_assert(sizeof(kMapNames) / sizeof(kMapNames[0]) == MAP_COUNT, "a name for every map");

struct FrameStats {
    StageTimes ms;
    std::uint32_t emitted[MAP_COUNT] = {};   // paths of the global and the caustic pass
    std::uint32_t stored[MAP_COUNT] = {};    // photons that reached each map
    std::uint32_t capacity[MAP_COUNT] = {};  // room in each map; photons beyond it were dropped
    std::uint32_t environmentPaths = 0;      // photon paths the environment emitted
    std::uint32_t environmentHits = 0;       // ... whose first ray met the scene
    Exchange exchange;                       // what the devices exchanged (several devices)

    std::uint64_t emittedPaths() const { return sum(emitted); }
    std::uint64_t storedPhotons() const { return sum(stored); }
    // The photons each map kept, "12 global, 3 caustic" (of `stored`, or only those within capacity).
    std::string storedList(bool withinCapacity = false) const {
        std::string list;
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            std::uint32_t n = withinCapacity ? std::min(stored[m], capacity[m]) : stored[m];
            list += (m == 0 ? "" : ", ") + std::to_string(n) + " " + kMapNames[m];
        }
        return list;
    }

private:
    static std::uint64_t sum(const std::uint32_t (&values)[MAP_COUNT]) {
        std::uint64_t total = 0;
        for (std::uint32_t v : values) {
            total += v;
        }
        return total;
    }
};

// A readback of both photon maps: each map's photons in cell order, as the maps keep them and
// decoded (without ids, which the maps do not keep), and its cell ranges (cellStart has cells + 1
// entries and indexes that map's photons).
struct PhotonMaps {
    std::vector<MapPhoton> stored[MAP_COUNT];
    std::vector<Photon> photons[MAP_COUNT];
    std::vector<std::uint32_t> cellStart[MAP_COUNT];
};

struct GridStats {
    std::uint32_t cells = 0;
    std::uint32_t occupied = 0;
    std::uint32_t maxPerCell = 0;
    double meanPerOccupied = 0.0;
};

GridStats gridStats(const std::vector<std::uint32_t>& cellStart);

class Renderer {
public:
    // One or more devices (at least one); the first runs everything after the photon pass.
    explicit Renderer(std::vector<std::unique_ptr<Device>> devices,
                      std::unique_ptr<Collective> collective = createHostCollective());
    ~Renderer();

    // The devices' backends, "cpu" or "cpu,cpu", and what they run on.
    std::string name() const;
    std::string deviceName() const;
    std::size_t deviceCount() const { return devices_.size(); }
    Device& device(std::size_t index = 0) { return *devices_.at(index); }
    // The processes rendering together (MPI) and whether this one holds the image (the first):
    // the others' image(), rawImage() and readbacks throw std::logic_error.
    std::uint32_t processes() const { return collective_->processes(); }
    bool leads() const { return collective_->leads(); }
    // Whether to stop after this frame, the same in every process (Collective::agreeToStop):
    // several processes render the same frames.
    StopVote agreeToStop(int request, bool leaderDone) { return collective_->agreeToStop(request, leaderDone); }

    // Changing any of these restarts accumulation; uploads and allocations happen in prepare().
    void setScene(Scene scene);  // moved in: a large scene is not copied again
    void setSettings(const RenderSettings& settings);
    void setCamera(const CameraDesc& camera);
    // The camera moved: under settings().reproject the next frame carries each pixel's history to
    // where its surface is now seen (shared/reproject.h) and nothing restarts; otherwise as
    // setCamera(). Several moves before a frame reproject from the last frame's camera.
    void moveCamera(const CameraDesc& camera);
    void resetAccumulation();
    // This renderer's share of each frame's photon paths (by default all, or this process's share
    // where several render together). Its devices split the share again.
    void setPathSplit(const PathSplit& split);

    // Uploads the scene and allocates for the settings if anything changed. Checks every device's
    // limits (memory, buffer sizes) first and throws InputError, before any work, if the request
    // cannot fit.
    void prepare();
    void renderFrame();

    // A frame that the caller submits itself (the windowed viewer, whose one Vulkan device records
    // into the viewer's command buffer: vk::VulkanDevice::recordInto): beginFrame() prepares and
    // returns its parameters; recordFrame() runs the stages as renderFrame() does, without waiting
    // for them; endFrame() takes its results once it has run, grows the photon maps as
    // renderFrame() does and counts the frame. It returns false, without counting, for a first
    // frame that lost photons: the next frame repeats it with room for them (only if mayRepeat).
    // renderFrame() is exactly beginFrame(), the stages, endFrame(). Change nothing in between.
    const FrameParams& beginFrame();
    void recordFrame();
    bool endFrame(const FrameResult& result, bool mayRepeat = true);

    // The image of the frames rendered since the last reset (linear radiance): denoised when the
    // settings say so (denoises()), running the denoise stage first if the last frame did not.
    Image image();
    // The mean of the frames without the denoiser.
    Image rawImage();
    // Whether every frame runs the denoise stage (a viewer shows every frame); otherwise image()
    // runs it on demand, once for the frames it shows.
    void setDenoiseEachFrame(bool each) { denoiseEachFrame_ = each; }
    std::uint32_t accumulatedFrames() const { return accumulated_; }
    const FrameStats& lastFrameStats() const { return stats_; }
    const Scene& scene() const { return scene_; }
    const RenderSettings& settings() const { return settings_; }
    const CameraDesc& camera() const { return camera_; }
    const PhotonBudget& budget() const { return budget_; }
    const FrameParams& lastFrameParams() const { return params_; }
    const BufferPlan& bufferPlan() const { return plan_; }

    // Stage outputs of the last frame, for tests and tools.
    PhotonMaps readPhotonMaps();
    std::vector<HitPoint> readHitPoints();
    std::vector<SppmPixel> readSppmPixels();
    // The auxiliary images (shared/aov.h), when the settings keep them (keepsAovs()); else empty.
    std::vector<PixelAov> readAovs();
    Image readFrame();

    // What the first device may allocate now, and where its buffers live (Device's).
    MemoryLimits memoryLimits() { return devices_.front()->memoryLimits(); }
    bool buffersInHostMemory() const { return devices_.front()->buffersInHostMemory(); }
    // Whether every device runs on the host's cores: the default photon count follows it.
    bool runsOnCpu() const;

private:
    // The stages in order on the first device; with denoiseOnly, only the denoise stage, over
    // the last frame's image. Several devices: the photon pass on each, the exchange, the rest on
    // the first (runSharedFrame()), the same with several processes.
    FrameResult runFrame(const FrameParams& params, bool denoiseOnly = false);
    FrameResult runSharedFrame(const FrameParams& params);
    // The stages of `params` that this part of a frame runs, the others skipped in their places.
    void runStages(Device& device, const FrameParams& params, bool denoiseOnly, std::uint32_t first,
                   std::uint32_t last);
    // A new scene or settings: plan and measure again, and start the frames and their seeds over.
    void restart();
    // Runs the denoise stage over the image, unless it ran for this image already.
    void denoiseImage();
    Image readImage(std::uint32_t binding);
    // Throws std::logic_error in a process that does not hold the image.
    void requireLeader(const char* what) const;
    // A per-pixel buffer's elements, as the last frame left them.
    template <typename T>
    std::vector<T> readPerPixel(std::uint32_t binding);
    // The footprints and first radii of the camera, if it, the scene or the settings changed.
    void measureRadii();
    // Grows a photon map that came within 80% of its capacity (GPU devices drop photons beyond
    // it). Returns true if photons were dropped this frame.
    bool growPhotonMaps();

    std::vector<std::unique_ptr<Device>> devices_;
    std::unique_ptr<Collective> collective_;
    Scene scene_;
    RenderSettings settings_;
    CameraDesc camera_;
    PhotonBudget budget_;
    Footprints footprints_;       // of the camera and image (automatic radii)
    EstimatorPolicy policy_;      // the radii frame by frame
    PathSplit split_;
    bool footprintsDirty_ = true;
    FrameParams params_{};
    FrameStats stats_;
    Exchange exchange_;           // of the frame in flight
    std::uint32_t frameIndex_ = 0;   // frames since the scene or settings were set: seeds the RNG
    std::uint32_t accumulated_ = 0;  // frames in the running mean
    bool sceneDirty_ = true;
    bool allocationDirty_ = true;
    std::uint32_t allocatedWidth_ = 0;
    std::uint32_t allocatedHeight_ = 0;
    PhotonBudget allocatedBudget_;
    BufferPlan plan_;                     // the first device's
    std::vector<BufferPlan> devicePlans_;  // each device's, as allocated
    std::uint32_t grownCapacity_[MAP_COUNT] = {};  // capacities raised by growPhotonMaps()
    bool warnedDropped_ = false;
    bool denoiseEachFrame_ = false;
    bool reprojecting_ = false;     // the camera moved since the last frame, which reprojects
    CameraDesc previousCamera_;     // ... from this, the last frame's
    std::uint32_t denoisedFrames_ = 0;  // accumulated_ when the denoise stage last ran (0: never)
};

}  // namespace photon
