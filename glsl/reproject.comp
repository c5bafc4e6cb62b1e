#version 460
// Stage reproject: one invocation per pixel for each of its passes (REPROJECT_PASS_*), which the
// host dispatches in order with a barrier between them.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/reproject.h"
#include "glsl/dispatch.h"

layout(local_size_x = PIXEL_TILE_X, local_size_y = PIXEL_TILE_Y) in;
layout(push_constant) uniform Push { uint pass; } push;

void main() {
    uint pixel;
    if (!pixelOfInvocation(pixel)) {
        return;
    }
    reprojectPass(pixel, push.pass);
}
