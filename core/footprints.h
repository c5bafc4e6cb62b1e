// Automatic query radii that know the image: a pixel's footprint (its width at its visible point,
// shared/sppm.h pixelFootprint) measured over a sparse grid of pixel centres, traced on the host
// with the shared eye pass. A radius of a few footprints blurs a few pixels wherever the camera
// looks, whatever the scene's extent (an object far outside the view changes nothing).
#pragma once

#include <cstdint>

#include "frame_setup.h"
#include "scene.h"
#include "settings.h"

namespace photon {

struct Footprints {
    float median = 0.0f;  // over the sampled pixels whose eye path ended on a surface
    float high = 0.0f;    // the 90th percentile
    bool any = false;     // some sampled eye path ended on a surface
};

// Traces up to 48 × 36 pixel centres of the image.
Footprints measureFootprints(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings);

// Automatic radii in footprints (of the median footprint) for the single-frame estimators.
inline constexpr float kAutoRadiusFootprints = 8.0f;         // the global map
inline constexpr float kAutoCausticRadiusFootprints = 4.0f;  // the caustic map

// A bounded grid's query reaches this many cells from its centre (validateForScene).
inline constexpr float kBoundedGridReachCells = 6.0f;

// sppm starts each pixel at its own footprint times a number of footprints chosen so that a
// first disc holds about this many photons if they spread over the image (clamped to the range
// below): few enough to keep detail, enough that the first frames are not all noise.
inline constexpr float kSppmFirstPhotons[MAP_COUNT] = {64.0f, 16.0f};
inline constexpr float kSppmFirstFootprintsMin[MAP_COUNT] = {1.5f, 1.0f};
inline constexpr float kSppmFirstFootprintsMax[MAP_COUNT] = {16.0f, 8.0f};

// What the frame's radii start from: the query radius of each map for the single-frame estimators
// (settings, else the footprints, else 1% of the scene's diagonal), and under sppm the radius the
// grid's cells must first hold.
struct FrameRadii {
    float radius[MAP_COUNT] = {};          // GridParams.radius (sppm: the radius the grid's cells follow)
    float firstRadius[MAP_COUNT] = {};     // sppm: the first radius of every pixel; 0: from its footprint
    float firstFootprints[MAP_COUNT] = {}; // sppm: the first radius in footprints at the pixel
};

// `budget` gives the photons of each map per frame (sppm's first radii).
FrameRadii firstFrameRadii(const Scene& scene, const RenderSettings& settings, const Footprints& footprints,
                           const PhotonBudget& budget);

// sppm: the radius the next frame's cells follow, the median of the pixels that have photons
// (the upper end of its bin of COUNTER_SPPM_HISTOGRAM), but at least 1/kSppmCellReach of the
// largest radius of a pixel with photons (COUNTER_SPPM_RADIUS_*), so that no query visits more
// than about (2.5 kSppmCellReach + 1)³ cells, whatever the radii: the histogram's bins end at
// 2^±32, and --radius 1e12 once made every query of a 64×48 image walk 233³ cells of the median.
// 0 if no pixel has photons.
inline constexpr float kSppmCellReach = 8.0f;
float sppmCellRadius(const std::uint32_t* histogram, float largest);
// The median alone.
float sppmMedianRadius(const std::uint32_t* histogram);

}  // namespace photon
