// What the viewer's own passes (viewer/) share with their shaders, in the dialect of
// shared/portable.h: binding numbers, push constants, and the fixed point of the photon dots.
#ifndef PHOTON_GLSL_VIEWER_H
#define PHOTON_GLSL_VIEWER_H

#include "shared/constants.h"

PH_NAMESPACE_BEGIN

// The display pass's descriptor set (viewer_display.frag).
PH_CONST uint DISPLAY_BINDING_IMAGE = 0u;  // the backend's accumulation: vec4 of radiance per pixel
PH_CONST uint DISPLAY_BINDING_DOTS = 1u;   // the photon dots: three uint per pixel, fixed point

// What the display pass shows (DisplayPush::source).
PH_CONST uint DISPLAY_IMAGE = 0u;  // the accumulated image
PH_CONST uint DISPLAY_DOTS = 1u;   // the photon dots
// The auxiliary images, read from the backend's AOV buffer bound as the image (a PixelAov is
// four vec4: albedo and depth, normal and coverage, ...).
PH_CONST uint DISPLAY_ALBEDO = 2u;
PH_CONST uint DISPLAY_NORMAL = 3u;  // as a normal map: 0.5 n + 0.5
PH_CONST uint DISPLAY_DEPTH = 4u;   // 2^exposure / (1 + depth), black where nothing was met
PH_CONST uint DISPLAY_AOV_VEC4S = 4u;

// The photon-dots pass's own set (set 1 of its layout; set 0 is the backend's).
PH_CONST uint DOTS_BINDING_DOTS = 0u;
PH_CONST float DOTS_FIXED_POINT = 1024.0f;  // dot-buffer units per unit of brightness

struct DisplayPush {
    uint width; uint height;              // the rendered image (the accumulation buffer)
    uint targetWidth; uint targetHeight;  // the framebuffer it is shown in, scaled to fill it
    uint source; uint curve;              // DISPLAY_*; TONEMAP_*
    float scale; float pad0;              // 2^exposure
};

struct DotsPush {
    uint map;               // MAP_GLOBAL or MAP_CAUSTIC: one dispatch each
    float brightness;       // brightness per watt of photon power
    float depthTolerance;   // a dot shows if its depth is within this fraction of the surface
                            // seen through its pixel; 0: every photon shows (no occlusion)
    float pad0;
};

PH_NAMESPACE_END

#ifdef __cplusplus
namespace photon {
static_assert(sizeof(DisplayPush) == 32, "DisplayPush: 8 words of push constants");
static_assert(sizeof(DotsPush) == 16, "DotsPush: 4 words of push constants");
}  // namespace photon
#endif

#endif
