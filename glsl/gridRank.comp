#version 460
// STAGE_BUILD_GRID, step 4 of the deterministic build (per map): each place's photon ranked within its chunk (shared/photon_map.h).
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_map.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;
layout(push_constant) uniform Push { uint map; } push;

void main() {
    uint i = invocationIndex();
    if (i < storedPhotons(push.map)) {
        rankInChunk(push.map, i);
    }
}
