#version 460
// STAGE_BUILD_GRID, step 5 of the deterministic build (per map): the chunks of the larger cells merged (shared/photon_map.h).
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_map.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;
layout(push_constant) uniform Push { uint map; } push;

void main() {
    uint i = invocationIndex();
    if (i < storedPhotons(push.map)) {
        mergeChunks(push.map, i);
    }
}
