#include "footprints.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "frame_setup.h"
#include "shared/eye_trace.h"
#include "shared/sppm.h"

namespace photon {

Footprints measureFootprints(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings) {
    RenderSettings s = settings;
    s.pixelCenter = true;
    PhotonBudget budget;
    Bindings bindings{};
    bindings.params = makeFrameParams(scene, camera, s, budget, 0, 0, FrameRadii{});
    bindSceneArrays(bindings, scene);
    std::uint32_t columns = std::min<std::uint32_t>(48, s.width);
    std::uint32_t rows = std::min<std::uint32_t>(36, s.height);
    std::vector<float> widths;
    widths.reserve(std::size_t(columns) * rows);
    for (std::uint32_t j = 0; j < rows; ++j) {
        for (std::uint32_t i = 0; i < columns; ++i) {
            std::uint32_t x = (2 * i + 1) * s.width / (2 * columns);
            std::uint32_t y = (2 * j + 1) * s.height / (2 * rows);
            HitPoint hp = tracePixel(bindings, y * s.width + x);
            if (hp.material != NONE) {
                float w = pixelFootprint(bindings.params.camera, s.height, hp.position);
                if (w > 0.0f && std::isfinite(w)) {
                    widths.push_back(w);
                }
            }
        }
    }
    Footprints f;
    if (widths.empty()) {
        return f;
    }
    std::sort(widths.begin(), widths.end());
    f.median = widths[widths.size() / 2];
    f.high = widths[std::min(widths.size() - 1, widths.size() * 9 / 10)];
    f.any = true;
    return f;
}

FrameRadii firstFrameRadii(const Scene& scene, const RenderSettings& settings, const Footprints& footprints,
                           const PhotonBudget& budget) {
    FrameRadii r;
    float fallback = 0.01f * scene.diagonal();
    float given[MAP_COUNT] = {settings.radius, settings.causticRadius};
    if (settings.estimator == Estimator::Sppm) {
        double pixels = double(settings.width) * double(settings.height);
        // Caustic photons: the caustic pass's, or the few of the global pass that make caustic paths.
        double photons[MAP_COUNT] = {double(budget.globalPaths),
                                     budget.splitCaustics ? double(budget.causticPaths) : 0.1 * budget.globalPaths};
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            double perPixel = std::max(photons[m], 1.0) / pixels;
            double f = std::sqrt(double(kSppmFirstPhotons[m]) / (3.14159265358979 * perPixel));
            r.firstFootprints[m] = float(std::clamp(f, double(kSppmFirstFootprintsMin[m]), double(kSppmFirstFootprintsMax[m])));
            r.firstRadius[m] = given[m];
            r.radius[m] = given[m] > 0.0f ? given[m]
                          : footprints.any ? footprints.median * r.firstFootprints[m]
                                           : (m == MAP_GLOBAL ? fallback : 0.5f * fallback);
        }
        return r;
    }
    float global = given[MAP_GLOBAL] > 0.0f ? given[MAP_GLOBAL]
                   : footprints.any        ? kAutoRadiusFootprints * footprints.median
                                           : fallback;
    r.radius[MAP_GLOBAL] = global;
    r.radius[MAP_CAUSTIC] = given[MAP_CAUSTIC] > 0.0f ? given[MAP_CAUSTIC]
                            : footprints.any          ? kAutoCausticRadiusFootprints * footprints.median
                                                      : 0.5f * global;
    if (settings.grid == GridKind::Bounded) {
        // An automatic radius stays within what the bounded grid's query reaches (a given one is
        // refused by validateForScene instead).
        glm::vec3 extent = scene.boundsMax - scene.boundsMin;
        float cell = std::max({extent.x, extent.y, extent.z}) / float(settings.gridResolution);
        for (std::uint32_t m = 0; m < MAP_COUNT; ++m) {
            if (given[m] <= 0.0f) {
                r.radius[m] = std::min(r.radius[m], kBoundedGridReachCells * cell);
            }
        }
    }
    return r;
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
