// Progressive photon mapping in the probabilistic form of Knaus & Zwicker ("Progressive Photon
// Mapping: A Probabilistic Approach", TOG 2011): every frame is an independent photon-map render
// with its own radius, the radii shrink as r²(i+1) = r²(i)·(i + α)/(i + 1), and the image is the
// plain average of the frames. Bias and variance both vanish as frames grow, for α ∈ (0, 1).
#ifndef PHOTON_SHARED_PROGRESSIVE_H
#define PHOTON_SHARED_PROGRESSIVE_H

#include "constants.h"

PH_NAMESPACE_BEGIN

// Radius of frame i, from the first frame's radius r0.
PH_FN float progressiveRadius(float r0, float alpha, uint i) {
    float r2 = r0 * r0;
    for (uint j = 0u; j < i; ++j) {
        r2 *= (float(j) + alpha) / (float(j) + 1.0f);
    }
    return sqrt(r2);
}

// Running mean: the average of n earlier frames and this one.
PH_FN vec4 accumulateMean(vec4 mean, vec4 frame, uint n) {
    if (n == 0u) {
        return frame;
    }
    return mean + (frame - mean) / float(n + 1u);
}

// Whether this frame's gather starts sppm's statistics (sppm.h): its pixels then take their first
// radii from the photons (the gather's start variant, a compile-time constant on the GPUs, since
// the search's heap would cost every later frame's gather registers). A visible point that first
// appears in a later frame (a pixel's jittered ray that missed until then) starts at the
// even-spread guess.
PH_FN bool sppmStarts(uint estimator, uint view, uint accumulated) {
    return estimator == ESTIMATOR_SPPM && view != VIEW_GRID && accumulated == 0u;
}

PH_NAMESPACE_END

#endif
