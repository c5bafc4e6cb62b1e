// Turning a scene and settings into what the backends run: how many photons each pass emits,
// how much room the photon maps get, and each frame's FrameParams. Every backend receives the
// same FrameParams from here, so they differ only in how they schedule the work.
#pragma once

#include <algorithm>
#include <cstdint>

#include "core/scene/scene.h"
#include "core/settings/settings.h"
#include "shared/bindings.h"
#include "shared/layout.h"

namespace photon {

// Capacities and cells of each map. A map holds at most kMapCapacityMax photons (a share of 2^32),
// so that the offsets into the photon arrays of every map together stay within 32 bits; a request
// that large fails the memory check of most GPUs.
inline constexpr std::uint32_t kMapCapacityMax = std::uint32_t((std::uint64_t(1) << 32) / MAP_COUNT - 1u);
static_assert(std::uint64_t(kMapCapacityMax) * MAP_COUNT < (std::uint64_t(1) << 32), "photon offsets fit 32 bits");

struct PhotonBudget {
    std::uint32_t globalPaths = 0;            // photons emitted by the global pass per frame
    std::uint32_t causticPaths = 0;           // photons aimed at specular objects per frame
    std::uint32_t capacity[MAP_COUNT] = {};   // stored photons each map has room for
    std::uint32_t cells[MAP_COUNT] = {};      // cells of each map's grid (hashed: a power of two)
    bool splitCaustics = false;               // caustic paths come from the caustic pass only
    bool sppm = false;                        // the estimator keeps per-pixel statistics
    bool deterministic = false;               // each cell's photons in canonical order (photon_map.h)
    bool aovs = false;                        // the auxiliary images are kept (shared/aov.h)
    bool denoise = false;                     // the denoiser runs (shared/denoise.h)
    bool history = false;                     // the history follows the camera (shared/reproject.h)

    // The maps lie one after another, in map order, in the photon arrays and in cellStart
    // (each map's cells and an end entry).
    std::uint32_t photonOffset(std::uint32_t map) const { return sumBefore(capacity, map, 0u); }
    std::uint32_t cellOffset(std::uint32_t map) const { return sumBefore(cells, map, 1u); }
    std::uint32_t totalPaths() const { return globalPaths + causticPaths; }
    std::uint32_t totalCapacity() const { return photonOffset(MAP_COUNT); }
    std::uint32_t totalCellEntries() const { return cellOffset(MAP_COUNT); }
    std::uint32_t largestCapacity() const { return *std::max_element(capacity, capacity + MAP_COUNT); }
    std::uint32_t largestCells() const { return *std::max_element(cells, cells + MAP_COUNT); }

private:
    static std::uint32_t sumBefore(const std::uint32_t* values, std::uint32_t map, std::uint32_t extra) {
        std::uint64_t sum = 0;
        for (std::uint32_t m = 0; m < map; ++m) {
            sum += values[m] + std::uint64_t(extra);
        }
        return static_cast<std::uint32_t>(sum);
    }
};

PhotonBudget planPhotons(const Scene& scene, const RenderSettings& settings);

struct FrameRadii;  // estimator_policy.h

// A frame's photon paths shared by `ranks` renderers (GPUs): rank r traces the r-th of `ranks`
// consecutive index ranges. One renderer alone is rank 0 of 1.
struct PathSplit {
    std::uint32_t rank = 0;
    std::uint32_t ranks = 1;
};

// Parameters of one frame. frameIndex numbers frames since the renderer started (it seeds the
// random numbers); accumulated counts the frames already averaged (the progressive index);
// radii are the frame's radii as the estimator policy chose them (estimator_policy.h).
FrameParams makeFrameParams(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings,
                            const PhotonBudget& budget, std::uint32_t frameIndex, std::uint32_t accumulated,
                            const FrameRadii& radii, const PathSplit& split = {});

// The scene's arrays and a frame's parameters without photon maps, each pixel's ray through its
// centre: for tracing the scene on the host with the shared code (footprints, the glass region).
Bindings hostSceneBindings(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings);

// Narrows the parameters' paths (pathFirst, pathCount) to `split`'s rank's consecutive part of
// them: a process's share of a frame, then each of its devices' share of that.
void splitPaths(FrameParams& params, const PathSplit& split);

}  // namespace photon
