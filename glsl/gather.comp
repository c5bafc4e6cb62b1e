#version 460
// Stage gather: one invocation per pixel, the photon estimates at its hit point. The estimator,
// the global mode and sppm's start are specialization constants, so each pipeline variant carries
// only its own code (the k-nearest heap alone would otherwise burden every variant).
#extension GL_GOOGLE_include_directive : require
#define PH_PHOTON_MAPS_READONLY
#define PH_HIT_POINTS_READONLY
#include "shared/bindings.h"
#include "shared/sppm.h"
#include "glsl/dispatch.h"

layout(local_size_x = PIXEL_TILE_X, local_size_y = PIXEL_TILE_Y) in;
layout(constant_id = 1) const uint ESTIMATOR = 1u;    // ESTIMATOR_*
layout(constant_id = 2) const uint GLOBAL_MODE = 0u;  // GLOBAL_*
layout(constant_id = 3) const bool SPPM_START = false;  // sppmStarts

void main() {
    uint pixel;
    if (!pixelOfInvocation(pixel)) {
        return;
    }
    frameRadiance[pixel] = gatherStage(pixel, ESTIMATOR, GLOBAL_MODE, SPPM_START);
}
