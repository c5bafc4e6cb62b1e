// Participating media (Jensen & Christensen 1998; pbrt-v4's HomogeneousMedium): an absorption
// coefficient σa and a scattering coefficient σs per channel, scaled by a density grid in
// heterogeneous media (medium_grid.h), and Henyey–Greenstein scattering. A medium fills the
// inside of the objects whose material names it, or the scene (SceneInfo.medium) within a box.
// Paths carry the medium they are in (mediumAcross below).
//
// Photons fly freely through it (sampleFreeFlight) and scatter, leaving a photon in the volume
// map at each scattering; eye rays take the medium's transmittance exactly and collect the light
// it scatters towards them from the volume map (volume_estimate.h).
#ifndef PHOTON_SHARED_MEDIUM_H
#define PHOTON_SHARED_MEDIUM_H

#include "bindings.h"
#include "math.h"
#include "medium_grid.h"
#include "rng.h"
#include "spectral.h"

// Whether the scene may hold media: true, except in the kernels and pipelines made for scenes
// without any (the Vulkan tracing shaders' specialization constant SCENE_HAS_MEDIA, CUDA's
// no-media kernels), where every medium's code folds away and the kernels keep the registers they
// had before media existed.
#ifndef PH_SCENE_HAS_MEDIA
#define PH_SCENE_HAS_MEDIA true
#endif

PH_NAMESPACE_BEGIN

// −ln(u) for u ∈ (0, 1] without a transcendental function, so that every backend computes the
// same bits (as expNegative): u = 2^k · m with m ∈ [√½, √2), ln m = 2 atanh(s) with
// s = (m − 1)/(m + 1) ∈ (−0.172, 0.172), a series to s¹¹ (relative error < 1e-7).
PH_FN float negativeLog(float u) {
    if (!(u > 0.0f)) {
        return FLOAT_MAX;
    }
    uint bits = floatBitsToUint(u);
    int k = int((bits >> 23u) & 255u) - 127;
    float m = uintBitsToFloat((bits & 0x007FFFFFu) | 0x3F800000u);
    if (m > 1.41421356f) {
        m *= 0.5f;
        k += 1;
    }
    float s = (m - 1.0f) / (m + 1.0f);
    float s2 = s * s;
    PH_PRECISE float lnM = 2.0f * s * (1.0f + s2 * (0.33333333f + s2 * (0.2f + s2 * (0.14285714f + s2 * (0.11111111f + s2 * 0.09090909f)))));
    PH_PRECISE float result = -(float(k) * 0.693147181f + lnM);
    return result;
}

// Whether a frame's scene holds media (the hosts choose the kernels for scenes without them): the
// volume map has room only then.
PH_FN bool sceneHasMedia(PH_IN(FrameParams) params) { return params.grids[MAP_VOLUME].photonCapacity > 0u; }

PH_FN vec3 expNegative3(vec3 x) { return vec3(expNegative(x.x), expNegative(x.y), expNegative(x.z)); }

// Medium `index` at the frame's wavelengths (coefficients lifted like reflectances, spectral.h).
PH_FN Medium loadMedium(BUF_PARAM uint index) {
    Medium md = BUF(media)[index];
    md.absorption = spectralFromRgb(BUF_ARG md.absorption);
    md.scattering = spectralFromRgb(BUF_ARG md.scattering);
    return md;
}

PH_FN vec3 extinctionOf(PH_IN(Medium) md) { return md.absorption + md.scattering; }

// The part [tEnter, tExit] of the ray o + t·d, t ∈ [0, tMax], inside the medium's box (slab
// test); empty when tEnter ≥ tExit.
PH_FN vec2 mediumSpan(PH_IN(Medium) md, vec3 o, vec3 d, float tMax) {
    vec3 inverse = vec3(1.0f) / d;
    vec3 t0 = (md.lower - o) * inverse;
    vec3 t1 = (md.upper - o) * inverse;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float tEnter = max(max(near.x, near.y), max(near.z, 0.0f));
    float tExit = min(min(far.x, far.y), min(far.z, tMax));
    return vec2(tEnter, tExit);
}

// Henyey–Greenstein's phase function of the angle between the direction light travelled and the
// one it scatters to: (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}).
PH_FN float henyeyGreenstein(float cosTheta, float g) {
    PH_PRECISE float denominator = max(1.0f + g * g - 2.0f * g * cosTheta, 1.0e-12f);
    // precise here and below: Mesa would fold and reorder the constant factors (portable.h).
    PH_PRECISE float phase = (1.0f - g * g) * (0.25f * INV_PI) / (denominator * sqrt(denominator));
    return phase;
}

// A direction scattered from `travel` (the direction the light moved along) with density
// henyeyGreenstein(cos θ, g): cos θ by inverting its cdf (Henyey & Greenstein 1941).
PH_FN vec3 sampleHenyeyGreenstein(vec3 travel, float g, float u1, float u2) {
    PH_PRECISE float cosTheta;
    if (abs(g) < 1.0e-3f) {
        cosTheta = 1.0f - 2.0f * u1;
    } else {
        PH_PRECISE float q = (1.0f - g * g) / (1.0f - g + 2.0f * g * u1);
        cosTheta = clamp((1.0f + g * g - q * q) / (2.0f * g), -1.0f, 1.0f);
    }
    return directionAroundAxis(travel, 1.0f - cosTheta, u2);
}

// The outcome of a photon's flight through a medium along a span [tEnter, tExit].
struct FreeFlight {
    vec3 weight;    // what the path's power is multiplied by
    float t;        // where it scattered (scatters) or tExit
    bool scatters;  // a real collision before tExit
};

// Free-flight sampling with several channels (pbrt-v3's HomogeneousMedium::Sample): the optical
// depth by one channel's extinction picked at random, weighted by the density averaged over the
// three (one-sample multiple importance sampling), so the estimate is unbiased in every channel
// and the weight stays bounded. At a collision the weight carries σs·T/p (absorption ends
// nothing: it scales the power); past tExit, T/P. In a heterogeneous medium ρ(x) scales σs and
// every channel's σt alike and cancels from the weight: the same flight in the density integral
// D instead of the length (medium_grid.h). A medium that only absorbs takes its transmittance
// exactly. Two draws when the medium scatters.
PH_FN FreeFlight sampleFreeFlight(BUF_PARAM PH_IN(Medium) md, vec3 o, vec3 d, float tEnter, float tExit,
                                  PH_INOUT(Rng) rng) {
    FreeFlight f;
    f.t = tExit;
    f.scatters = false;
    vec3 sigmaT = extinctionOf(md);
    if (isBlack(md.scattering)) {
        f.weight = expNegative3(sigmaT * densityIntegral(BUF_ARG md, o, d, tEnter, tExit));
        return f;
    }
    float pick = rngNext(rng) * 3.0f;
    float sigma = pick < 1.0f ? sigmaT.x : pick < 2.0f ? sigmaT.y : sigmaT.z;
    float depth = sigma > 0.0f ? negativeLog(1.0f - rngNext(rng)) / sigma : FLOAT_MAX;
    DensityWalk walk = walkDensity(BUF_ARG md, o, d, tEnter, tExit, depth);
    if (walk.reached) {
        vec3 transmittance = expNegative3(sigmaT * depth);
        vec3 density = sigmaT * transmittance;
        PH_PRECISE vec3 weight = md.scattering * transmittance * (3.0f / (density.x + density.y + density.z));
        f.weight = weight;
        f.t = walk.t;
        f.scatters = true;
        return f;
    }
    vec3 transmittance = expNegative3(sigmaT * walk.integral);
    float passes = transmittance.x + transmittance.y + transmittance.z;
    PH_PRECISE vec3 weight = transmittance * (3.0f / passes);
    f.weight = passes > 0.0f ? weight : vec3(0.0f);
    return f;
}

// The medium a path is in after it crosses a surface of material m (wo: where it came from,
// facing or not the geometric normal n as the primitive defines it, outward for closed objects;
// `to`: where it goes). Crossing into a closed object (spheres, meshes) takes the object's medium
// (none for glass without one), crossing out of it the scene's; quads and planes are thin sheets
// and leave the medium as it was. One level: an object inside a medium-filled object sees the
// scene's medium outside itself.
PH_FN uint mediumAcross(BUF_PARAM uint current, PH_IN(Material) m, uint kind, vec3 n, vec3 wo, vec3 to) {
    if (!PH_SCENE_HAS_MEDIA) {
        return current;
    }
    float side = dot(wo, n);
    bool crosses = side * dot(to, n) < 0.0f;
    if (!crosses || kind == PRIM_QUAD || kind == PRIM_PLANE) {
        return current;
    }
    return side > 0.0f ? m.medium : BUF(params).scene.medium;
}

// The transmittance of medium `medium` (NONE: none) from o along d for `distance`, within its box:
// what reaches through it along a shadow ray.
PH_FN_OUTLINED vec3 mediumTransmittance(BUF_PARAM uint medium, vec3 o, vec3 d, float distance) {
    if (!PH_SCENE_HAS_MEDIA || medium == NONE) {
        return vec3(1.0f);
    }
    Medium md = loadMedium(BUF_ARG medium);
    vec2 span = mediumSpan(md, o, d, distance);
    if (!(span.x < span.y)) {
        return vec3(1.0f);
    }
    return expNegative3(extinctionOf(md) * densityIntegral(BUF_ARG md, o, d, span.x, span.y));
}

PH_NAMESPACE_END

#endif
