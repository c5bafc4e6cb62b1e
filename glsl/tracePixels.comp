#version 460
// Stage tracePixels: one invocation per pixel, leaving its hit point.
#extension GL_GOOGLE_include_directive : require
// Pipelines for scenes without media are made with this false: their code folds away (medium.h).
layout(constant_id = 4) const bool SCENE_HAS_MEDIA = true;
#define PH_SCENE_HAS_MEDIA SCENE_HAS_MEDIA
#include "shared/bindings.h"
#include "shared/eye_trace.h"
#include "glsl/dispatch.h"

layout(local_size_x = EYE_TILE_X, local_size_y = PIXEL_TILE_Y) in;

void main() {
    uint pixel;
    if (!pixelOfInvocation(pixel)) {
        return;
    }
    hitPoints[pixel] = tracePixel(pixel);
}
