// Spectral rendering (FLAG_SPECTRAL). Each frame draws one set of three wavelengths for all of its
// paths, as pbrt-v4's SPPM draws one per pass (core/spectral/ picks them: a hero from the visible
// distribution and two companions a third of its cdf apart, the hero stepping along a golden-ratio
// sequence from frame to frame). Every vec3 of light transport then holds radiance, power or
// reflectance at λ0, λ1, λ2 instead of red, green and blue, so that the photon and eye passes run
// unchanged:
//   - RGB values enter through the spectral primaries (fromRgb: three non-negative spectra that
//     sum to one and project to the sRGB primaries, Mallett & Yuksel 2019), where materials are
//     textured (surfaceAt; hitPointShading for the glossy colour), where photons leave lights
//     and where eye paths read lights;
//   - the gather leaves in linear sRGB (toRgb: the CIE 1931 observer over the samples' densities),
//     before anything is averaged across frames.
// A dispersive material's index of refraction depends on the wavelength: dispersion.h.
#ifndef PHOTON_SHARED_SPECTRAL_H
#define PHOTON_SHARED_SPECTRAL_H

#include "bindings.h"

PH_NAMESPACE_BEGIN

PH_FN bool isSpectral(uint flags) { return (flags & FLAG_SPECTRAL) != 0u; }

// An RGB value (reflectance, radiance, power, absorption) at the frame's wavelengths.
PH_FN vec3 spectralFromRgb(BUF_PARAM vec3 rgb) {
    if (!isSpectral(BUF(params).flags)) {
        return rgb;
    }
    return vec3(dot(vec3(BUF(params).spectrum.fromRgb0), rgb), dot(vec3(BUF(params).spectrum.fromRgb1), rgb),
                dot(vec3(BUF(params).spectrum.fromRgb2), rgb));
}

// Radiance at the frame's wavelengths in linear sRGB.
PH_FN vec3 rgbFromSpectral(BUF_PARAM vec3 s) {
    if (!isSpectral(BUF(params).flags)) {
        return s;
    }
    return vec3(dot(vec3(BUF(params).spectrum.toRgb0), s), dot(vec3(BUF(params).spectrum.toRgb1), s),
                dot(vec3(BUF(params).spectrum.toRgb2), s));
}

// A material's colours at the frame's wavelengths (the textured ones: call it after texturing).
PH_FN Material spectralMaterial(BUF_PARAM PH_IN(Material) m) {
    Material s = m;
    if (isSpectral(BUF(params).flags)) {
        s.albedo = spectralFromRgb(BUF_ARG m.albedo);
        s.specular = spectralFromRgb(BUF_ARG m.specular);
        s.emission = spectralFromRgb(BUF_ARG m.emission);
        s.attenuation = spectralFromRgb(BUF_ARG m.attenuation);
    }
    return s;
}

PH_FN uint pathChannel(uint pathFlags) { return (pathFlags >> PATH_CHANNEL_SHIFT) & 3u; }

PH_FN uint withPathChannel(uint pathFlags, uint channel) {
    return (pathFlags & ~(3u << PATH_CHANNEL_SHIFT)) | (channel << PATH_CHANNEL_SHIFT);
}

PH_NAMESPACE_END

#endif
