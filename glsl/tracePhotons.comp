#version 460
// Stage tracePhotons: one invocation per photon path. Each stored photon takes the next slot of
// its map (an atomic counter); slots beyond the map's capacity are counted but not written, so
// the host learns how much room the frame needed.
#extension GL_GOOGLE_include_directive : require
#include "shared/bindings.h"
#include "shared/photon_trace.h"
#include "glsl/dispatch.h"

layout(local_size_x = GROUP_SIZE) in;

void appendPhoton(uint map, Photon photon) {
    uint counter = map == MAP_GLOBAL ? COUNTER_STORED_GLOBAL : COUNTER_STORED_CAUSTIC;
    uint slot = atomicAdd(counters[counter], 1u);
    if (slot < params.grids[map].photonCapacity) {
        photons[params.grids[map].photonOffset + slot] = photon;
    }
}

void main() {
    uint index = invocationIndex();
    if (index >= params.globalPaths + params.causticPaths) {
        return;
    }
    PhotonPath path = startPhotonPath(index);
    while (photonPathAlive(path)) {
        Photon photon;
        uint store = photonBounce(path, photon);
        if ((store & STORE_GLOBAL) != 0u) {
            appendPhoton(MAP_GLOBAL, photon);
        }
        if ((store & STORE_CAUSTIC) != 0u) {
            appendPhoton(MAP_CAUSTIC, photon);
        }
    }
}
