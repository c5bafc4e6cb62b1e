// What the estimators decide on the host between frames, in one place: the first radius of each
// photon map (from the camera's pixel footprints, footprints.h, or the settings), how the
// progressive estimator shrinks it frame by frame (Knaus & Zwicker), and for sppm the photon
// passes a frame counts as and the radius its grid cells follow, fed back from the histogram of
// the pixels' radii that the frame before left in the counters.
#pragma once

#include <cstdint>

#include "core/frame/footprints.h"
#include "core/frame/frame_setup.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon {

// A bounded grid's query reaches this many cells from its centre (validateForScene); the beam
// estimate of the volume map one cell from the cells a ray crosses.
inline constexpr float kBoundedGridReachCells = 6.0f;
inline constexpr float boundedGridReachCells(std::uint32_t map) { return map == MAP_VOLUME ? 1.0f : kBoundedGridReachCells; }

// A frame's radii: the query radius of each map (GridParams.radius; sppm: the radius the grid's
// cells follow) and sppm's per-map parameters (FrameParams.sppm).
struct FrameRadii {
    float radius[MAP_COUNT] = {};
    SppmMapParams sppm[MAP_COUNT] = {};
    float branchShrink = 1.0f;  // FrameParams::branchShrink
};

// The first frame's radii: a map's radius from the settings, else from the footprints, else 1%
// of the scene's diagonal (the caustic map's: half the global one). `budget` gives the photons of
// each map per frame (sppm's first radii and passes).
FrameRadii firstFrameRadii(const Scene& scene, const RenderSettings& settings, const Footprints& footprints,
                           const PhotonBudget& budget);

// sppm: the radius the next frame's cells follow, the median of the pixels that have photons
// (the upper end of its bin of COUNTER_SPPM_HISTOGRAM), but at least 1/kSppmCellReach of the
// largest radius of a pixel with photons (COUNTER_SPPM_RADIUS), so that no query visits more
// than about (2.5 kSppmCellReach + 1)³ cells, whatever the radii: the histogram's bins end at
// 2^±32, and --radius 1e12 once made every query of a 64×48 image walk 233³ cells of the median.
// 0 if no pixel has photons.
inline constexpr float kSppmCellReach = 8.0f;
float sppmCellRadius(const std::uint32_t* histogram, float largest);
// The median alone.
float sppmMedianRadius(const std::uint32_t* histogram);

// The radii frame after frame of one accumulation.
class EstimatorPolicy {
public:
    // Starts from the first frame's radii (the camera, the scene or the settings changed).
    void start(const FrameRadii& first) { first_ = first, current_ = first; }
    const FrameRadii& first() const { return first_; }

    // The radii of the frame that follows `accumulated` frames of the running image.
    FrameRadii frame(const RenderSettings& settings, std::uint32_t accumulated);

    // What a frame that ran tells the next (sppm: the radius its cells follow), from its counters.
    void observe(const RenderSettings& settings, const std::uint32_t* counters);

private:
    FrameRadii first_;
    FrameRadii current_;  // sppm: the radii of this accumulation's last frame, fed back
};

}  // namespace photon
