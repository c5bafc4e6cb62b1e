// Turning a scene and settings into what the backends run: how many photons each pass emits,
// how much room the photon maps get, and each frame's FrameParams. Every backend receives the
// same FrameParams from here, so they differ only in how they schedule the work.
#pragma once

#include <cstdint>

#include "scene.h"
#include "settings.h"
#include "shared/layout.h"

namespace photon {

struct PhotonBudget {
    std::uint32_t globalPaths = 0;            // photons emitted by the global pass per frame
    std::uint32_t causticPaths = 0;           // photons aimed at specular objects per frame
    std::uint32_t capacity[MAP_COUNT] = {};   // stored photons each map has room for
    std::uint32_t cells[MAP_COUNT] = {};      // cells of each map's grid (hashed: a power of two)
    bool splitCaustics = false;               // caustic paths come from the caustic pass only
    bool sppm = false;                        // the estimator keeps per-pixel statistics

    std::uint32_t photonOffset(std::uint32_t map) const { return map == MAP_GLOBAL ? 0u : capacity[MAP_GLOBAL]; }
    std::uint32_t cellOffset(std::uint32_t map) const { return map == MAP_GLOBAL ? 0u : cells[MAP_GLOBAL] + 1u; }
    std::uint32_t totalPaths() const { return globalPaths + causticPaths; }
    std::uint32_t totalCapacity() const { return capacity[MAP_GLOBAL] + capacity[MAP_CAUSTIC]; }
    // cellStart entries of both maps: each map's cells plus one end entry.
    std::uint32_t totalCellEntries() const { return cells[MAP_GLOBAL] + cells[MAP_CAUSTIC] + 2u; }
};

PhotonBudget planPhotons(const Scene& scene, const RenderSettings& settings);

struct FrameRadii;  // footprints.h

// A frame's photon paths shared by `ranks` renderers (GPUs): rank r traces the r-th of `ranks`
// consecutive index ranges. One renderer alone is rank 0 of 1.
struct PathSplit {
    std::uint32_t rank = 0;
    std::uint32_t ranks = 1;
};

// Parameters of one frame. frameIndex numbers frames since the renderer started (it seeds the
// random numbers); accumulated counts the frames already averaged (the progressive index);
// radii are the frame's query radii (footprints.h: the first frame's; the progressive estimator
// shrinks them here, sppm on the device).
FrameParams makeFrameParams(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings,
                            const PhotonBudget& budget, std::uint32_t frameIndex, std::uint32_t accumulated,
                            const FrameRadii& radii, const PathSplit& split = {});

}  // namespace photon
