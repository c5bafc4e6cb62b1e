// The one interface every program talks to. A backend (cpu/, cuda/, vulkan/) only allocates
// buffers and schedules the stages; what a frame computes is decided here and in shared/, and
// what it needs (core/frame/buffers.h), its statistics and the readbacks of its results are worked out
// here once for all backends.
//
// A frame runs the stages of shared/stages.h in their order (runFrame() here), each named alike
// in every backend.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/frame/buffers.h"
#include "core/frame/estimator_policy.h"
#include "core/frame/footprints.h"
#include "core/frame/frame_setup.h"
#include "core/image/image.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"
#include "shared/layout.h"
#include "shared/stages.h"

namespace photon {

// Milliseconds of each stage of one frame (device time on GPUs), by STAGE_*.
struct StageTimes {
    double ms[STAGE_COUNT] = {};
    double& operator[](std::uint32_t stage) { return ms[stage]; }
    double operator[](std::uint32_t stage) const { return ms[stage]; }
    double total() const {
        double sum = 0.0;
        for (double t : ms) {
            sum += t;
        }
        return sum;
    }
};

// What a backend reports of a frame it ran: the stage times and the counters buffer.
struct FrameResult {
    StageTimes ms;
    std::uint32_t counters[COUNTER_COUNT] = {};
};

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

struct BackendOptions {
    std::string device;       // Vulkan: index or part of the name; CUDA: index
    bool validation = false;  // Vulkan: enable the validation layer; any message is an error
    bool parity = false;      // CUDA: kernels without FMA contraction, bit-exact with the CPU backend
};

class Backend {
public:
    virtual ~Backend() = default;

    virtual std::string name() const = 0;        // "cpu", "cuda", "vulkan"
    virtual std::string deviceName() const = 0;  // the processor or GPU it runs on

    // Changing any of these restarts accumulation; uploads and allocations happen in prepare().
    void setScene(Scene scene);  // moved in: a large scene is not copied again
    void setSettings(const RenderSettings& settings);
    void setCamera(const CameraDesc& camera);
    // The camera moved: under settings().reproject the next frame carries each pixel's history to
    // where its surface is now seen (shared/reproject.h) and nothing restarts; otherwise as
    // setCamera(). Several moves before a frame reproject from the last frame's camera.
    void moveCamera(const CameraDesc& camera);
    void resetAccumulation();
    // This renderer's share of each frame's photon paths (multi-GPU rendering; default: all).
    void setPathSplit(const PathSplit& split);

    // Uploads the scene and allocates for the settings if anything changed. Checks the machine's
    // limits (memory, buffer sizes) first and throws InputError, before any work, if the request
    // cannot fit.
    void prepare();
    void renderFrame();

    // A frame that the caller records and submits itself (the windowed viewer, through
    // vk::VulkanBackend::recordFrame): beginFrame() prepares and returns its parameters;
    // endFrame() takes its stats once it has run, grows the photon maps as renderFrame() does and
    // counts the frame. It returns false, without counting, for a first frame that lost photons:
    // the next frame repeats it with room for them (only if mayRepeat). renderFrame() is exactly
    // beginFrame(), the stages (runFrame()), endFrame(). Change nothing between the two calls.
    const FrameParams& beginFrame();
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

    // What this backend may allocate now (what it holds already counts as free).
    virtual MemoryLimits memoryLimits() = 0;

    // Whether the buffers live in host memory (the CPU backend): then the memory check already
    // counts the image's host copies (adjustPlan), else they are checked against host memory apart.
    virtual bool buffersInHostMemory() const { return false; }

    // Whether its stages run on the host's cores (the CPU backend, Vulkan on a software device
    // such as lavapipe): the default photon count follows it (choosePhotons).
    virtual bool runsOnCpu() const { return false; }

protected:
    // Entries a backend adds for its own scheduling (Vulkan: the levels of its scan in cellStart).
    virtual void adjustPlan(BufferPlan& plan, const PhotonBudget& budget) { (void)plan, (void)budget; }
    // The scene's arrays (sceneArray()) into their buffers, sized as the plan says.
    virtual void uploadScene(const Scene& scene, const BufferPlan& plan) = 0;
    // Every buffer that is not the scene's, sized as the plan says; contents need not be kept.
    virtual void allocate(const BufferPlan& plan, const PhotonBudget& budget, std::uint32_t width,
                          std::uint32_t height) = 0;
    // One frame: beginStages(), runStage() for each stage of shared/stages.h in order, endStages()
    // (which waits for the frame and returns its times and counters).
    virtual void beginStages(const FrameParams& params) = 0;
    virtual void runStage(std::uint32_t stage, const FrameParams& params) = 0;
    // A stage this frame leaves out, in its place in the order (timers that run from stage to
    // stage record it as taking no time).
    virtual void skipStage(std::uint32_t stage) { (void)stage; }
    virtual FrameResult endStages() = 0;
    // `bytes` bytes of the buffer at `binding`, from byte `offset`, after every earlier frame.
    virtual void readBuffer(std::uint32_t binding, std::uint64_t offset, std::uint64_t bytes, void* data) = 0;

private:
    // The stages in order; with denoiseOnly, only the denoise stage, over the last frame's image.
    FrameResult runFrame(const FrameParams& params, bool denoiseOnly = false);
    // Runs the denoise stage over the image, unless it ran for this image already.
    void denoiseImage();
    Image readImage(std::uint32_t binding);
    // A per-pixel buffer's elements, as the last frame left them.
    template <typename T>
    std::vector<T> readPerPixel(std::uint32_t binding);
    // The footprints and first radii of the camera, if it, the scene or the settings changed.
    void measureRadii();
    // Grows a photon map that came within 80% of its capacity (GPU backends drop photons beyond
    // it). Returns true if photons were dropped this frame.
    bool growPhotonMaps();

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
    std::uint32_t frameIndex_ = 0;   // frames since the scene or settings were set: seeds the RNG
    std::uint32_t accumulated_ = 0;  // frames in the running mean
    bool sceneDirty_ = true;
    bool allocationDirty_ = true;
    std::uint32_t allocatedWidth_ = 0;
    std::uint32_t allocatedHeight_ = 0;
    PhotonBudget allocatedBudget_;
    BufferPlan plan_;
    std::uint32_t grownCapacity_[MAP_COUNT] = {};  // capacities raised by growPhotonMaps()
    bool warnedDropped_ = false;
    bool denoiseEachFrame_ = false;
    bool reprojecting_ = false;     // the camera moved since the last frame, which reprojects
    CameraDesc previousCamera_;     // ... from this, the last frame's
    std::uint32_t denoisedFrames_ = 0;  // accumulated_ when the denoise stage last ran (0: never)
};

}  // namespace photon
