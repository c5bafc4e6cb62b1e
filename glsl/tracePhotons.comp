#version 460
// Stage tracePhotons: a pool of invocations over the photon paths of both passes (this renderer's
// share), each taking the next path when its own ends.
#extension GL_GOOGLE_include_directive : require
// Pipelines for scenes without media are made with this false: their code folds away (medium.h).
layout(constant_id = 4) const bool SCENE_HAS_MEDIA = true;
#define PH_SCENE_HAS_MEDIA SCENE_HAS_MEDIA
#include "shared/bindings.h"
#include "shared/photon_trace.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;

void main() {
    tracePhotonPool();
}
