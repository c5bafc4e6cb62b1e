// Stochastic progressive photon mapping (Hachisuka & Jensen, "Stochastic Progressive Photon
// Mapping", SIGGRAPH Asia 2009; as pbrt-v4's SPPMIntegrator). Each frame every pixel has a visible
// point (its hit point: jittered, through the lens, along one of glass's two paths), and for each
// photon map a radius R, a photon count N and a flux τ that persist from frame to frame. The M
// photons within R this frame, with reflected flux Φ = Σ β f Φp, update them as
//     N' = N + αM,    R' = R √(N' / (N + M)),    τ' = (τ + Φ) R'² / R²,
// so radii shrink where photons are found and not where there are none. A frame of a million
// photons counts as B photon passes of SPPM_BATCH_PATHS each (FrameParams.batches*), as
// Hachisuka's smallppm traces its photons in passes of a thousand: the update runs B times, each
// with a B-th of the frame's photons and of their flux, thinned to the shrinking disc under the
// estimate's own assumption of a density that is even across the disc. Radii then shrink with the
// photons traced (as the total photon count to the power -(1 - α)/2), not with the frames, and a
// caustic's focus sharpens at any photons per frame. The gather stage finds the frame's photons
// (SppmFrame) and the accumulate stage applies the update, so that GPUs that split a frame's
// photons can sum what they found in between. After k frames the pixel's radiance is the mean
// direct light plus τ / (k π R²) for each map. Direct light stays with the shadow rays of the
// eye pass.
//
// The first radius of a pixel is a number of pixel footprints at its visible point (the host picks
// it from the photon density, FrameParams.firstFootprints*), so it knows the image, not the
// scene's bounds. Radii then differ from pixel to pixel by orders of magnitude: the grid's cells
// follow the median radius of the pixels with photons (each frame's GridParams.radius, from the
// histogram COUNTER_SPPM_HISTOGRAM of the frame before), a wider query visits more cells,
// filtered (estimate.h), so that its cost stays that of its disc, and a pixel without photons is
// held to the median.
#ifndef PHOTON_SHARED_SPPM_H
#define PHOTON_SHARED_SPPM_H

#include "gather.h"
#include "progressive.h"

PH_NAMESPACE_BEGIN

// The width of one pixel at distance |p - camera| (a pinhole's footprint there).
PH_FN float pixelFootprint(PH_IN(Camera) camera, uint height, vec3 p) {
    return length(p - camera.position) * (2.0f * camera.tanHalfFovY / float(height));
}

PH_FN SppmPixel emptySppmPixel() {
    SppmPixel s;
    s.direct = vec3(0.0f);
    s.countGlobal = 0.0f;
    s.fluxGlobal = vec3(0.0f);
    s.radiusGlobal = 0.0f;
    s.fluxCaustic = vec3(0.0f);
    s.radiusCaustic = 0.0f;
    s.countCaustic = 0.0f;
    s.pad0 = 0u;
    s.pad1 = 0u;
    s.pad2 = 0u;
    return s;
}

// One map's statistics of one pixel.
struct SppmEstimate {
    vec3 flux;
    float radius;
    float count;
};

// The radius a pixel's query of `map` uses this frame: its statistics' radius, the first radius
// when it has none yet, and for a pixel that has found no photon yet (its τ is 0) at most the
// radius the cells follow: where a map has no light (most pixels, for the caustic map) queries
// stay as cheap as the lit pixels' ones. The gather and the update both ask it, so that GPUs that
// sum their photons between the two agree on it.
PH_FN float sppmQueryRadius(BUF_PARAM uint map, PH_IN(SppmEstimate) e, float footprint) {
    bool global = map == MAP_GLOBAL;
    float r = e.radius;
    if (r == 0.0f) {
        float first = global ? BUF(params).firstRadiusGlobal : BUF(params).firstRadiusCaustic;
        r = first > 0.0f ? first : footprint * (global ? BUF(params).firstFootprintsGlobal : BUF(params).firstFootprintsCaustic);
    }
    if (e.count == 0.0f) {
        r = min(r, BUF(params).grids[map].radius);
    }
    return r;
}

// This frame's photons M of `map` within the radius, and their flux Φ (in .xyz and .w).
PH_FN vec4 sppmFramePhotons(BUF_PARAM uint map, PH_IN(Shading) s, vec3 weight, float r, float u) {
    if (BUF(params).grids[map].photonCapacity == 0u) {
        return vec4(0.0f);
    }
    vec4 q = radiusQuery(BUF_ARG BUF(params).grids[map], s, r, KERNEL_BOX, u, true);
    return vec4(weight * vec3(q) * estimateScale(s), q.w);
}

// The frame's M photons and flux Φ of `map` (all renderers' together), folded into the pixel's
// statistics as B photon passes (FrameParams.batches*).
PH_FN void sppmUpdate(BUF_PARAM uint map, float r, float m, vec3 phi, PH_INOUT(SppmEstimate) e) {
    if (BUF(params).grids[map].photonCapacity == 0u) {
        return;
    }
    e.radius = r;
    if (m > 0.0f) {
        uint batches = max(map == MAP_GLOBAL ? BUF(params).batchesGlobal : BUF(params).batchesCaustic, 1u);
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
        PH_ATOMIC_MAX(BUF(counters)[COUNTER_SPPM_RADIUS_GLOBAL + map], bits);
        int bin = clamp(int(bits >> 23u) - 127 + int(SPPM_RADIUS_BINS / 2u), 0, int(SPPM_RADIUS_BINS) - 1);
        PH_ATOMIC_ADD(BUF(counters)[COUNTER_SPPM_HISTOGRAM + map * SPPM_RADIUS_BINS + uint(bin)], 1u);
    }
}

// The pixel's statistics before this frame.
PH_FN SppmPixel sppmPixelBefore(BUF_PARAM uint pixel) {
    // (Not a ?: of a buffer element and a local: glslang gives the two struct types apart.)
    SppmPixel state = emptySppmPixel();
    if (BUF(params).accumulated > 0u) {
        state = BUF(sppmPixels)[pixel];
    }
    return state;
}

PH_FN SppmEstimate sppmEstimateOf(PH_IN(SppmPixel) state, uint map) {
    SppmEstimate e;
    e.flux = map == MAP_GLOBAL ? state.fluxGlobal : state.fluxCaustic;
    e.radius = map == MAP_GLOBAL ? state.radiusGlobal : state.radiusCaustic;
    e.count = map == MAP_GLOBAL ? state.countGlobal : state.countCaustic;
    return e;
}

PH_FN void storeSppmEstimate(PH_INOUT(SppmPixel) state, uint map, PH_IN(SppmEstimate) e) {
    if (map == MAP_GLOBAL) {
        state.fluxGlobal = e.flux;
        state.radiusGlobal = e.radius;
        state.countGlobal = e.count;
    } else {
        state.fluxCaustic = e.flux;
        state.radiusCaustic = e.radius;
        state.countCaustic = e.count;
    }
}

// The gather stage under sppm: this frame's photons at the pixel's visible point, into
// sppmFrame (the accumulate stage folds them into the statistics). Returns this frame's own
// estimate Φ / (πR²) of this renderer's photons (frameRadiance).
PH_FN vec3 gatherSppm(BUF_PARAM uint pixel) {
    HitPoint hp = BUF(hitPoints)[pixel];
    uint view = BUF(params).view;
    vec3 frame = viewShowsDirect(view) ? hp.direct : vec3(0.0f);
    vec4 found[MAP_COUNT];
    found[MAP_GLOBAL] = vec4(0.0f);
    found[MAP_CAUSTIC] = vec4(0.0f);
    if (hp.material != NONE) {
        SppmPixel state = sppmPixelBefore(BUF_ARG pixel);
        Shading s = hitPointShading(BUF_ARG hp);
        Rng rng = rngCreate(pixel, BUF(params).frameIndex, BUF(params).seed, STREAM_GATHER);
        float u = rngNext(rng);
        float footprint = pixelFootprint(BUF(params).camera, BUF(params).height, hp.position);
        for (uint map = 0u; map < MAP_COUNT; ++map) {
            float r = sppmQueryRadius(BUF_ARG map, sppmEstimateOf(state, map), footprint);
            found[map] = sppmFramePhotons(BUF_ARG map, s, hp.weight, r, u);
            if (viewShowsMap(view, map) && r > 0.0f) {
                frame += vec3(found[map]) * (INV_PI / (r * r));
            }
        }
    }
    SppmFrame f;
    f.fluxGlobal = vec3(found[MAP_GLOBAL]);
    f.countGlobal = found[MAP_GLOBAL].w;
    f.fluxCaustic = vec3(found[MAP_CAUSTIC]);
    f.countCaustic = found[MAP_CAUSTIC].w;
    BUF(sppmFrame)[pixel] = f;
    return frame;
}

// The update of a pixel's statistics from the frame's photons (sppmFrame), in the accumulate
// stage.
PH_FN SppmPixel sppmAccumulate(BUF_PARAM uint pixel) {
    HitPoint hp = BUF(hitPoints)[pixel];
    SppmPixel state = sppmPixelBefore(BUF_ARG pixel);
    state.direct += (hp.direct - state.direct) / float(BUF(params).accumulated + 1u);
    if (hp.material != NONE) {
        SppmFrame f = BUF(sppmFrame)[pixel];
        float footprint = pixelFootprint(BUF(params).camera, BUF(params).height, hp.position);
        for (uint map = 0u; map < MAP_COUNT; ++map) {
            SppmEstimate e = sppmEstimateOf(state, map);
            float m = map == MAP_GLOBAL ? f.countGlobal : f.countCaustic;
            vec3 phi = map == MAP_GLOBAL ? f.fluxGlobal : f.fluxCaustic;
            sppmUpdate(BUF_ARG map, sppmQueryRadius(BUF_ARG map, e, footprint), m, phi, e);
            storeSppmEstimate(state, map, e);
        }
    }
    BUF(sppmPixels)[pixel] = state;
    return state;
}

// The pixel's image after `frames` frames.
PH_FN vec3 sppmRadiance(PH_IN(SppmPixel) state, uint frames, uint view) {
    vec3 radiance = viewShowsDirect(view) ? state.direct : vec3(0.0f);
    float k = float(frames);
    if (viewShowsMap(view, MAP_GLOBAL) && state.radiusGlobal > 0.0f) {
        radiance += state.fluxGlobal * (INV_PI / (k * state.radiusGlobal * state.radiusGlobal));
    }
    if (viewShowsMap(view, MAP_CAUSTIC) && state.radiusCaustic > 0.0f) {
        radiance += state.fluxCaustic * (INV_PI / (k * state.radiusCaustic * state.radiusCaustic));
    }
    return radiance;
}

// The accumulate stage for every estimator: the running mean of the frames, or under sppm (other
// than the grid view, which shows each frame's cells) the image from the pixel's statistics.
PH_FN vec4 accumulatePixel(BUF_PARAM uint pixel) {
    uint n = BUF(params).accumulated;
    if (BUF(params).estimator == ESTIMATOR_SPPM && BUF(params).view != VIEW_GRID) {
        return vec4(sppmRadiance(sppmAccumulate(BUF_ARG pixel), n + 1u, BUF(params).view), 1.0f);
    }
    return accumulateMean(BUF(accumulation)[pixel], BUF(frameRadiance)[pixel], n);
}

// The gather stage for every estimator and global mode (sppm: direct mode only).
PH_FN vec3 gatherStage(BUF_PARAM uint pixel, uint estimator, uint globalMode) {
    if (estimator == ESTIMATOR_SPPM && BUF(params).view != VIEW_GRID) {
        return gatherSppm(BUF_ARG pixel);
    }
    return gatherPixel(BUF_ARG pixel, estimator, globalMode);
}

PH_NAMESPACE_END

#endif
