#include "core/frame/estimator_policy.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "core/frame/scene_settings.h"
#include "shared/progressive.h"

namespace photon {
namespace {

// Each photon map's rules, a value per map, from its row in shared/constants.h (PH_MAPS):
// - the automatic radii in footprints (of the median footprint) of the single-frame estimators;
// - where no footprint could be measured, the global map's radius is 1% of the scene's diagonal,
//   and every other map's its share of it;
// - sppm starts each pixel at the disc that would hold this many photons at the density about it
//   (sppm.h): few enough to keep detail, enough that the first frames are not all noise (16
//   caustic photons made the Cornell box's first frames noisier than radii from the footprints).
//   The footprints that would hold them if photons spread evenly over the image (clamped to the
//   range) are the first frame's cell size and the radius of a pixel with no photons about it.
#define PH_MAP_AUTO(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) autoFootprints,
#define PH_MAP_FALLBACK(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) fallbackShare,
#define PH_MAP_SPPM_PHOTONS(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) sppmPhotons,
#define PH_MAP_SPPM_MIN(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) sppmMin,
#define PH_MAP_SPPM_MAX(NAME, id, name, radiusFlag, autoFootprints, fallbackShare, sppmPhotons, sppmMin, sppmMax) sppmMax,
constexpr float kAutoRadiusFootprints[] = {PH_MAPS(PH_MAP_AUTO)};
constexpr float kFallbackShare[] = {PH_MAPS(PH_MAP_FALLBACK)};
constexpr std::uint32_t kSppmFirstPhotons[] = {PH_MAPS(PH_MAP_SPPM_PHOTONS)};
constexpr float kSppmFirstFootprintsMin[] = {PH_MAPS(PH_MAP_SPPM_MIN)};
constexpr float kSppmFirstFootprintsMax[] = {PH_MAPS(PH_MAP_SPPM_MAX)};
static_assert(sizeof(kAutoRadiusFootprints) == MAP_COUNT * sizeof(float) && sizeof(kFallbackShare) == MAP_COUNT * sizeof(float) &&
                  sizeof(kSppmFirstPhotons) == MAP_COUNT * sizeof(std::uint32_t) &&
                  sizeof(kSppmFirstFootprintsMin) == MAP_COUNT * sizeof(float) &&
                  sizeof(kSppmFirstFootprintsMax) == MAP_COUNT * sizeof(float),
              "a value for every map");

// sppm: a frame's paths of a map count as one photon pass per SPPM_BATCH_PATHS (sppm.h).
std::uint32_t sppmPasses(std::uint32_t paths) {
    return std::clamp<std::uint32_t>((paths + SPPM_BATCH_PATHS / 2) / SPPM_BATCH_PATHS, 1u, SPPM_BATCHES_MAX);
}

// The volume map's first beam radius, whatever the estimator: its footprints at the median
// footprint (the beam's disc lies across the camera ray, so a pixel's width is its scale), or its
// share of the fallback; within a bounded grid's cell, which is as far as the beam estimate reaches
// from the cells a ray crosses. Its frames then shrink it by Knaus and Zwicker's schedule (frame()).
float firstBeamRadius(const Scene& scene, const RenderSettings& settings, const Footprints& footprints, float fallback) {
    float given = mapRadius(settings, MAP_VOLUME);
    if (given > 0.0f) {
        return given;
    }
    float r = footprints.any ? kAutoRadiusFootprints[MAP_VOLUME] * footprints.median : kFallbackShare[MAP_VOLUME] * fallback;
    if (settings.grid == GridKind::Bounded) {
        glm::vec3 extent = scene.boundsMax - scene.boundsMin;
        r = std::min(r, std::max({extent.x, extent.y, extent.z}) / float(settings.gridResolution));
    }
    return r;
}

// An automatic radius stays within what the bounded grid's query reaches (boundedGridReachCells;
// a given one is refused by validateForScene instead). sppm's pixels start within it and only
// shrink, so its later frames stay within it too.
void clampToBoundedGrid(FrameRadii& r, const Scene& scene, const RenderSettings& settings) {
    if (settings.grid != GridKind::Bounded) {
        return;
    }
    glm::vec3 extent = scene.boundsMax - scene.boundsMin;
    float cell = std::max({extent.x, extent.y, extent.z}) / float(settings.gridResolution);
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        if (mapRadius(settings, m) <= 0.0f) {
            r.radius[m] = std::min(r.radius[m], boundedGridReachCells(m) * cell);
        }
    }
}

}  // namespace

FrameRadii firstFrameRadii(const Scene& scene, const RenderSettings& settings, const Footprints& footprints,
                           const PhotonBudget& budget) {
    FrameRadii r;
    // Photons of each map per frame: the caustic map's come from the caustic pass, or are the few
    // of the global pass that make caustic paths.
    // The volume map's come from the global pass.
    std::uint32_t paths[MAP_COUNT] = {budget.globalPaths, budget.splitCaustics ? budget.causticPaths : budget.globalPaths,
                                      budget.globalPaths};
    double photons[MAP_COUNT] = {double(budget.globalPaths),
                                 budget.splitCaustics ? double(budget.causticPaths) : 0.1 * budget.globalPaths,
                                 double(budget.globalPaths)};
    for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
        r.sppm[m].batches = sppmPasses(paths[m]);
    }
    float fallback = 0.01f * scene.diagonal();
    if (settings.estimator == Estimator::Sppm) {
        double pixels = double(settings.width) * double(settings.height);
        for (std::uint32_t m = 0; m < SURFACE_MAP_COUNT; ++m) {
            float given = mapRadius(settings, m);
            double perPixel = std::max(photons[m], 1.0) / pixels;
            double f = std::sqrt(double(kSppmFirstPhotons[m]) / (3.14159265358979 * perPixel));
            r.sppm[m].firstFootprints =
                float(std::clamp(f, double(kSppmFirstFootprintsMin[m]), double(kSppmFirstFootprintsMax[m])));
            r.sppm[m].firstRadius = given;
            r.sppm[m].firstNeighbours = kSppmFirstPhotons[m];
            float unseen = m == MAP_GLOBAL ? fallback : kFallbackShare[m] * fallback;
            r.radius[m] = given > 0.0f ? given : footprints.any ? footprints.median * r.sppm[m].firstFootprints : unseen;
        }
        r.radius[MAP_VOLUME] = firstBeamRadius(scene, settings, footprints, fallback);
        clampToBoundedGrid(r, scene, settings);
        return r;
    }
    for (std::uint32_t m = 0; m < SURFACE_MAP_COUNT; ++m) {
        float given = mapRadius(settings, m);
        // Without footprints a map falls back to its share of the global map's radius.
        float unseen = m == MAP_GLOBAL ? fallback : kFallbackShare[m] * r.radius[MAP_GLOBAL];
        r.radius[m] = given > 0.0f ? given : footprints.any ? kAutoRadiusFootprints[m] * footprints.median : unseen;
    }
    r.radius[MAP_VOLUME] = firstBeamRadius(scene, settings, footprints, fallback);
    clampToBoundedGrid(r, scene, settings);
    return r;
}

FrameRadii EstimatorPolicy::frame(const RenderSettings& settings, std::uint32_t accumulated) {
    switch (settings.estimator) {
        case Estimator::Sppm: {
            if (accumulated == 0) {
                current_ = first_;
            }
            FrameRadii r = current_;
            r.radius[MAP_VOLUME] = progressiveRadius(first_.radius[MAP_VOLUME], settings.alpha, accumulated);
            r.branchShrink = progressiveRadius(1.0f, settings.alpha, accumulated);
            return r;
        }
        case Estimator::Progressive: {
            FrameRadii r = first_;
            for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
                r.radius[m] = progressiveRadius(first_.radius[m], settings.alpha, accumulated);
            }
            r.branchShrink = progressiveRadius(1.0f, settings.alpha, accumulated);
            return r;
        }
        case Estimator::Cell:
        case Estimator::Radius:
        case Estimator::Knn: {
            FrameRadii r = first_;
            r.radius[MAP_VOLUME] = progressiveRadius(first_.radius[MAP_VOLUME], settings.alpha, accumulated);
            return r;
        }
    }
    throw std::logic_error("EstimatorPolicy: unknown estimator " + std::to_string(int(settings.estimator)));
}

void EstimatorPolicy::observe(const RenderSettings& settings, const std::uint32_t* counters) {
    if (settings.estimator != Estimator::Sppm) {
        return;
    }
    // The next frame's cells follow the median radius of the pixels that have photons, and the
    // largest (sppmCellRadius).
    for (std::uint32_t m = 0; m < SURFACE_MAP_COUNT; ++m) {
        float largest;
        std::memcpy(&largest, &counters[COUNTER_SPPM_RADIUS + m], sizeof largest);
        float r = sppmCellRadius(counters + COUNTER_SPPM_HISTOGRAM + m * SPPM_RADIUS_BINS, largest);
        if (r > 0.0f) {
            current_.radius[m] = r;
        }
    }
}

float sppmCellRadius(const std::uint32_t* histogram, float largest) {
    float median = sppmMedianRadius(histogram);
    if (median == 0.0f) {
        return 0.0f;
    }
    // A pixel's radius (finite: the counter holds float bits of one) reaches at most
    // kSppmCellReach cells from its centre.
    if (std::isfinite(largest) && largest > 0.0f) {
        median = std::max(median, largest / kSppmCellReach);
    }
    return median;
}

float sppmMedianRadius(const std::uint32_t* histogram) {
    std::uint64_t total = 0;
    for (std::uint32_t b = 0; b < SPPM_RADIUS_BINS; ++b) {
        total += histogram[b];
    }
    if (total == 0) {
        return 0.0f;
    }
    std::uint64_t seen = 0;
    for (std::uint32_t b = 0; b < SPPM_RADIUS_BINS; ++b) {
        seen += histogram[b];
        if (2 * seen >= total) {
            // Bin b holds radii in [2^e, 2^(e + 1)), e = b - SPPM_RADIUS_BINS / 2.
            return std::ldexp(1.0f, int(b) - int(SPPM_RADIUS_BINS / 2) + 1);
        }
    }
    return 0.0f;
}

}  // namespace photon
