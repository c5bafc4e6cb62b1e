#version 460
// Stage tracePhotons: one invocation per photon path of both passes (this renderer's share).
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_trace.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;

void main() {
    traceSharedPhotonPath(invocationIndex());
}
