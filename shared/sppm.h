// Stochastic progressive photon mapping (Hachisuka & Jensen, "Stochastic Progressive Photon
// Mapping", SIGGRAPH Asia 2009; as pbrt-v4's SPPMIntegrator). Each frame every pixel has a visible
// point (its hit point: jittered, through the lens, along one of glass's two paths), and for each
// photon map a radius R, a photon count N and a flux τ that persist from frame to frame. The M
// photons within R this frame, with reflected flux Φ = Σ β f Φp, update them as
//     N' = N + αM,    R' = R √(N' / (N + M)),    τ' = (τ + Φ) R'² / R²,
// so radii shrink where photons are found and not where there are none. A frame of a million
// photons counts as B photon passes of SPPM_BATCH_PATHS each (FrameParams.sppm[map].batches), as
// Hachisuka's smallppm traces its photons in passes of a thousand: the update runs B times, each
// with a B-th of the frame's photons and of their flux, thinned to the shrinking disc under the
// estimate's own assumption of a density that is even across the disc. Radii then shrink with the
// photons traced (as the total photon count to the power -(1 - α)/2), not with the frames, and a
// caustic's focus sharpens at any photons per frame. After k frames the pixel's radiance is the
// mean direct light plus τ / (k π R²) for each map. Direct light stays with the shadow rays of the
// eye pass.
//
// The first radius of a pixel comes from the photons around its visible point, as in Hachisuka,
// Ogaki & Jensen's progressive photon mapping (2008): the disc that would hold k photons of the
// first frame at their density there (sppmFirstRadius), so that a dense caustic starts sharp and a
// dim corner starts wide enough to see photons at all. It is bounded in pixel footprints, so it
// knows the image, not the scene's bounds. Radii then differ from pixel to pixel by orders of
// magnitude: the grid's cells follow the median radius of the pixels with photons (each frame's
// GridParams.radius, from the histogram COUNTER_SPPM_HISTOGRAM of the frame before), a wider query
// visits more cells, filtered (estimate.h), so that its cost stays that of its disc, and a pixel
// without photons is held to the median.
#ifndef PHOTON_SHARED_SPPM_H
#define PHOTON_SHARED_SPPM_H

#include "gather.h"
#include "history.h"
#include "progressive.h"

PH_NAMESPACE_BEGIN

// The width of one pixel at distance |p - camera| (a pinhole's footprint there).
PH_FN float pixelFootprint(PH_IN(Camera) camera, uint height, vec3 p) {
    return length(p - camera.position) * (2.0f * camera.tanHalfFovY / float(height));
}

PH_FN SppmPixel emptySppmPixel() {
    SppmPixel s;
    s.direct = vec3(0.0f);
    s.pad0 = 0.0f;
    for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
        s.maps[m].flux = vec3(0.0f);
        s.maps[m].radius = 0.0f;
    }
    for (uint m = 0u; m < SPPM_COUNT_SLOTS; ++m) {
        s.count[m] = 0.0f;
    }
    return s;
}

// The first radius at a visible point: the disc that would hold firstNeighbours photons of this
// frame at the density of the photons about it, read off the grid (cellDensityRadius: 27 cell
// lookups and no photon; a radius search over the photons doubled the first frame's gather, and
// the k-th nearest photon's distance collapses into a caustic's focus, the knn estimate's bias),
// within [SPPM_FIRST_MIN_FOOTPRINTS, SPPM_FIRST_MAX_GUESSES · the guess]; a point
// whose cells are empty keeps the even-spread guess, firstFootprints footprints.
PH_FN float sppmFirstRadius(BUF_PARAM uint map, PH_IN(Shading) s, float footprint) {
    GridParams grid = BUF(params).grids[map];
    float guess = footprint * BUF(params).sppm[map].firstFootprints;
    float r = cellDensityRadius(BUF_ARG grid, s.position, s.geometricNormal, float(BUF(params).sppm[map].firstNeighbours));
    if (r == 0.0f) {
        return guess;
    }
    return clamp(r, footprint * SPPM_FIRST_MIN_FOOTPRINTS, guess * SPPM_FIRST_MAX_GUESSES);
}

// One map's statistics of one pixel.
struct SppmEstimate {
    vec3 flux;
    float radius;
    float count;
};

// This frame's photons of `map` at the visible point, folded into its statistics. Returns the
// frame's own estimate Φ / (πR²) (for the single-frame image).
PH_FN vec3 sppmUpdate(BUF_PARAM uint map, PH_IN(Shading) s, vec3 weight, float footprint, float u, bool start,
                      PH_INOUT(SppmEstimate) e) {
    GridParams grid = BUF(params).grids[map];
    if (grid.photonCapacity == 0u) {
        return vec3(0.0f);
    }
    if (e.radius == 0.0f) {
        float first = BUF(params).sppm[map].firstRadius;
        if (first > 0.0f) {
            e.radius = first;
        } else if (start) {
            e.radius = sppmFirstRadius(BUF_ARG map, s, footprint);
        } else {
            e.radius = footprint * BUF(params).sppm[map].firstFootprints;
        }
    }
    if (e.count == 0.0f) {
        // A pixel that has found no photon yet (its τ is 0) is held to the radius the cells follow:
        // where a map has no light (most pixels, for the caustic map) queries stay as cheap as
        // the lit pixels' ones.
        e.radius = min(e.radius, grid.radius);
    }
    float r = e.radius;
    vec4 q = radiusQuery(BUF_ARG grid, s, r, KERNEL_BOX, u, true);
    vec3 phi = rgbFromSpectral(BUF_ARG weight * vec3(q) * estimateScale(s));  // frames average in RGB
    float m = q.w;
    vec3 frame = phi * (INV_PI / (r * r));
    if (m > 0.0f) {
        uint batches = max(BUF(params).sppm[map].batches, 1u);
        float alpha = BUF(params).alpha;
        float batchPhotons = m / float(batches);
        vec3 batchFlux = phi / float(batches);
        float area = 1.0f;  // (R_b / R)²: the part of the frame's disc that pass b still covers
        float count = e.count;
        vec3 flux = e.flux;
        for (uint b = 0u; b < batches; ++b) {
            float found = batchPhotons * area;
            float next = count + alpha * found;
            float shrink = next / (count + found);  // (R'/R)² of this pass
            flux = (flux + batchFlux * area) * shrink;
            area *= shrink;
            count = next;
        }
        e.flux = flux;
        e.radius = r * sqrt(area);
        e.count = count;
    }
    if (e.count > 0.0f) {
        uint bits = floatBitsToUint(e.radius);
        PH_TALLY_MAX(BUF(counters)[COUNTER_SPPM_RADIUS + map], bits);
        int bin = clamp(int(bits >> 23u) - 127 + int(SPPM_RADIUS_BINS / 2u), 0, int(SPPM_RADIUS_BINS) - 1);
        PH_TALLY_ADD(BUF(counters)[COUNTER_SPPM_HISTOGRAM + map * SPPM_RADIUS_BINS + uint(bin)], 1u);
    }
    return frame;
}

// One map's pass of the sppm gather at a pixel's visible point: its statistics read, updated
// with this frame's photons and written back. Each map's pass reads what it needs itself, so that
// nothing of the other map's pass is kept in registers across its loop over photons.
PH_FN vec3 gatherSppmMap(BUF_PARAM uint pixel, uint map, float u, bool start) {
    HitPoint hp = BUF(hitPoints)[pixel];
    Shading s = hitPointShading(BUF_ARG hp);
    SppmEstimate e;
    e.flux = vec3(0.0f);
    e.radius = 0.0f;
    e.count = 0.0f;
    if (historyFrames(BUF_ARG pixel) > 0u) {
        e.flux = BUF(sppmPixels)[pixel].maps[map].flux;
        e.radius = BUF(sppmPixels)[pixel].maps[map].radius;
        e.count = BUF(sppmPixels)[pixel].count[map];
    }
    float footprint = pixelFootprint(BUF(params).camera, BUF(params).height, hp.position);
    vec3 estimate = sppmUpdate(BUF_ARG map, s, hp.weight, footprint, u, start, e);
    BUF(sppmPixels)[pixel].maps[map].flux = e.flux;
    BUF(sppmPixels)[pixel].maps[map].radius = e.radius;
    BUF(sppmPixels)[pixel].count[map] = e.count;
    return estimate;
}

// The gather stage under sppm: updates the pixel's statistics and returns this frame's own
// estimate (frameRadiance; STAGE_ACCUMULATE makes the image from the statistics), and in w the
// luminance of its caustic map's part, which the denoiser leaves as it is (denoise.h).
PH_FN vec4 gatherSppm(BUF_PARAM uint pixel, bool start) {
    uint view = BUF(params).view;
    uint frames = historyFrames(BUF_ARG pixel);
    vec3 direct = rgbFromSpectral(BUF_ARG BUF(hitPoints)[pixel].direct);
    if (frames == 0u) {
        BUF(sppmPixels)[pixel] = emptySppmPixel();
    }
    vec3 mean = BUF(sppmPixels)[pixel].direct;
    BUF(sppmPixels)[pixel].direct = mean + (direct - mean) / float(frames + 1u);
    vec3 frame = viewShowsDirect(view) ? direct : vec3(0.0f);
    float caustic = 0.0f;
    if (BUF(hitPoints)[pixel].material != NONE) {
        Rng rng = rngCreate(pixel, BUF(params).frameIndex, BUF(params).seed, STREAM_GATHER);
        float u = rngNext(rng);
        vec3 shown = vec3(0.0f);
        for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
            vec3 estimate = gatherSppmMap(BUF_ARG pixel, m, u, start);
            shown += viewShowsMap(view, m) ? estimate : vec3(0.0f);
            caustic += m == MAP_CAUSTIC && viewShowsMap(view, m) ? luminanceOf(estimate) : 0.0f;
        }
        frame += shown;
    }
    return vec4(frame, caustic);
}

// The pixel's image after `frames` frames.
PH_FN vec3 sppmRadiance(PH_IN(SppmPixel) state, uint frames, uint view) {
    vec3 radiance = viewShowsDirect(view) ? state.direct : vec3(0.0f);
    float k = float(frames);
    for (uint m = 0u; m < SURFACE_MAP_COUNT; ++m) {
        float r = state.maps[m].radius;
        if (viewShowsMap(view, m) && r > 0.0f) {
            radiance += state.maps[m].flux * (INV_PI / (k * r * r));
        }
    }
    return radiance;
}

// STAGE_ACCUMULATE for every estimator: the running mean of the frames, or under sppm (other
// than the grid view, which shows each frame's cells) the image from the pixel's statistics.
PH_FN vec4 accumulatePixel(BUF_PARAM uint pixel) {
    uint n = historyFrames(BUF_ARG pixel);
    if (BUF(params).estimator == ESTIMATOR_SPPM && BUF(params).view != VIEW_GRID) {
        return vec4(sppmRadiance(BUF(sppmPixels)[pixel], n + 1u, BUF(params).view), 1.0f);
    }
    return accumulateMean(BUF(accumulation)[pixel], BUF(frameRadiance)[pixel], n);
}

// The gather stage for every estimator and global mode (sppm: direct mode only); `sppmStart`:
// sppmStarts of the frame. The frame's radiance, and in w what gatherSppm puts there (0 for the
// other estimators, whose maps the denoiser filters together).
PH_FN vec4 gatherStage(BUF_PARAM uint pixel, uint estimator, uint globalMode, bool sppmStart) {
    if (estimator == ESTIMATOR_SPPM && BUF(params).view != VIEW_GRID) {
        return gatherSppm(BUF_ARG pixel, sppmStart);
    }
    vec3 radiance = gatherPixel(BUF_ARG pixel, estimator, globalMode);
    return vec4(BUF(params).view == VIEW_GRID ? radiance : rgbFromSpectral(BUF_ARG radiance), 0.0f);
}

PH_NAMESPACE_END

#endif
