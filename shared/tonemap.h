// From linear radiance to display values: exposure, a tone curve, the sRGB transfer function.
// Display only: nothing compared between backends passes through here.
#ifndef PHOTON_SHARED_TONEMAP_H
#define PHOTON_SHARED_TONEMAP_H

#include "constants.h"

PH_NAMESPACE_BEGIN

PH_FN float srgbEncode(float c) {
    c = clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

// Exposure and the tone curve of one channel, before the transfer function: a linear display
// value (the clamp curve leaves it unclamped). `scale` is 2^exposure.
PH_FN float toneCurve(float radiance, float scale, uint curve) {
    float x = max(radiance * scale, 0.0f);
    if (curve == TONEMAP_REINHARD) {
        x = x / (1.0f + x);
    } else if (curve == TONEMAP_ACES) {
        x = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    }
    return x;
}

PH_FN vec3 tonemap(vec3 radiance, float scale, uint curve) {
    return vec3(srgbEncode(toneCurve(radiance.x, scale, curve)), srgbEncode(toneCurve(radiance.y, scale, curve)),
                srgbEncode(toneCurve(radiance.z, scale, curve)));
}

PH_NAMESPACE_END

#endif
