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

// `scale` is 2^exposure.
PH_FN vec3 tonemap(vec3 radiance, float scale, uint curve) {
    vec3 x = max(radiance * scale, vec3(0.0f));
    if (curve == TONEMAP_REINHARD) {
        x = x / (vec3(1.0f) + x);
    } else if (curve == TONEMAP_ACES) {
        x = (x * (2.51f * x + vec3(0.03f))) / (x * (2.43f * x + vec3(0.59f)) + vec3(0.14f));
    }
    return vec3(srgbEncode(x.x), srgbEncode(x.y), srgbEncode(x.z));
}

PH_NAMESPACE_END

#endif
