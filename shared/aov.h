// The auxiliary images (AOVs) of the eye pass, kept as running means beside the image by the
// accumulate stage when FLAG_AOVS is set: what a denoiser is guided by (denoise.h) and what
// `--aov` writes. As Open Image Denoise prescribes, the albedo and the normal are those of the
// first surface the eye path meets that is not a perfect mirror or glass (eye_trace.h,
// meetAovSurface: the albedo times the path's weight through mirrors and glass), and 0 where the
// path escaped or ended at an emitter first; the depth is the path's length to that surface, so
// that what a mirror or a glass ball shows has the depth of its image (a first hit's depth would
// make a refracted picture one smooth surface to the filter).
#ifndef PHOTON_SHARED_AOV_H
#define PHOTON_SHARED_AOV_H

#include "sppm.h"

PH_NAMESPACE_BEGIN

// What demodulation divides a pixel's radiance by, and multiplies it back with: the albedo where
// a surface ended its paths (at least DENOISE_MIN_ALBEDO), else 1.
PH_FN vec3 demodulation(vec3 albedo, bool surface) {
    return surface ? max(albedo, vec3(DENOISE_MIN_ALBEDO)) : vec3(1.0f);
}

PH_FN PixelAov emptyPixelAov() {
    PixelAov a;
    a.albedo = vec3(0.0f);
    a.depth = 0.0f;
    a.normal = vec3(0.0f);
    a.coverage = 0.0f;
    a.luminance = 0.0f;
    a.luminance2 = 0.0f;
    a.frames = 0.0f;
    a.pad1 = 0.0f;
    a.background = vec3(0.0f);
    a.pad2 = 0.0f;
    return a;
}

// This frame's auxiliary values of a pixel, from its hit point, folded into their means. The
// moments are of the frame's luminance without the caustic map's part (frameRadiance.w): a
// caustic's focus varies from frame to frame by more than its contrast with its surroundings, and
// a variance that counted it would open the luminance weight there and smear the focus (measured:
// Cornell box, focus energy 0.63 of the reference's, peak 0.25). Divided by each frame's own albedo
// instead of the mean's, a path that ends at a dark surface in one frame and a bright one in the
// next would make the variance huge. The frames whose path met no surface (an emitter, the sky)
// are kept apart as the pixel's background, which the denoiser adds back unfiltered: their light
// is not the albedo times what reaches a surface.
PH_FN void accumulateAov(BUF_PARAM uint pixel, vec4 frameRadiance) {
    HitPoint hp = BUF(hitPoints)[pixel];
    bool surface = hp.pathLength > 0.0f;
    vec3 albedo = hp.aovAlbedo;
    vec3 normal = surface ? octDecode(hp.aovNormal) : vec3(0.0f);
    // The light the denoiser filters: a frame with a surface's, without its caustic map's part (w).
    float l = surface ? luminanceOf(vec3(frameRadiance)) - frameRadiance.w : 0.0f;
    vec3 background = surface ? vec3(0.0f) : vec3(frameRadiance);
    uint n = historyFrames(BUF_ARG pixel);
    PixelAov a = emptyPixelAov();  // (a ?: of a local and a buffer struct is invalid SPIR-V from glslang)
    if (n > 0u) {
        a = BUF(aovs)[pixel];
    }
    // Divided, not multiplied by 1/k, so that no compiler fuses a step into an FMA.
    float k = float(n + 1u);
    a.albedo += (albedo - a.albedo) / k;
    a.normal += (normal - a.normal) / k;
    float hit = surface ? 1.0f : 0.0f;
    a.coverage += (hit - a.coverage) / k;
    if (hit > 0.0f) {
        // The mean over the frames that hit: coverage · k of them.
        PH_PRECISE float hits = a.coverage * k;
        a.depth += (hp.pathLength - a.depth) / max(hits, 1.0f);
    }
    PH_PRECISE float l2 = l * l;
    a.background += (background - a.background) / k;
    a.luminance += (l - a.luminance) / k;
    a.luminance2 += (l2 - a.luminance2) / k;
    a.frames = k;
    BUF(aovs)[pixel] = a;
}

// STAGE_ACCUMULATE: the image (accumulatePixel) and, under FLAG_AOVS, the auxiliary images.
PH_FN void accumulateStage(BUF_PARAM uint pixel) {
    BUF(accumulation)[pixel] = accumulatePixel(BUF_ARG pixel);
    if ((BUF(params).flags & FLAG_AOVS) != 0u) {
        accumulateAov(BUF_ARG pixel, BUF(frameRadiance)[pixel]);
    }
}

PH_NAMESPACE_END

#endif
