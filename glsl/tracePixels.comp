#version 460
// Stage tracePixels: one invocation per pixel, leaving its hit point.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/eye_trace.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;

void main() {
    uint pixel = invocationIndex();
    if (pixel >= params.width * params.height) {
        return;
    }
    hitPoints[pixel] = tracePixel(pixel);
}
