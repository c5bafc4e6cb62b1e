#version 460
// Stage accumulate: one invocation per pixel, folding this frame into the running mean (or, under
// sppm, making the image from the pixel's statistics), and its auxiliary images.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/aov.h"
#include "glsl/dispatch.h"

layout(local_size_x = PIXEL_TILE_X, local_size_y = PIXEL_TILE_Y) in;

void main() {
    uint pixel;
    if (!pixelOfInvocation(pixel)) {
        return;
    }
    accumulateStage(pixel);
}
