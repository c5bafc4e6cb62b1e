#version 460
// Photon dots, Wu's picture of the photon maps: every stored photon of a map projected to
// the screen (projectToPixel, the inverse of cameraRay) and added to its pixel, weighted by its
// power, so that a pixel's brightness is proportional to the photon flux it sees. A photon hidden
// behind the surface its pixel shows (the eye pass's hit point) is left out, unless occlusion is off.
// One invocation per stored photon, through the group counts gridArgs wrote for this map (for
// groups of GROUP_SIZE, as gridCount and gridScatter use them).
#extension GL_GOOGLE_include_directive : require
#define PH_PHOTON_MAPS_READONLY
#define PH_HIT_POINTS_READONLY
#include "shared/bindings.h"
#include "shared/eye_trace.h"
#include "shared/photon_map.h"
#include "glsl/dispatch.h"
#include "glsl/viewer.h"

layout(local_size_x = GROUP_SIZE) in;
layout(std430, set = 1, binding = DOTS_BINDING_DOTS) restrict buffer DotBuffer { uint dots[]; };
layout(push_constant) uniform Push { DotsPush push; };

void main() {
    uint i = invocationIndex();
    if (i >= storedPhotons(push.map)) {
        return;
    }
    GridParams grid = params.grids[push.map];
    Photon photon = decodeMapPhoton(sortedPhotons[grid.photonOffset + i], grid);
    vec3 screen = projectToPixel(params.camera, photon.position, params.width, params.height);
    if (screen.z <= 0.0f || screen.x < 0.0f || screen.y < 0.0f || screen.x >= float(params.width) ||
        screen.y >= float(params.height)) {
        return;
    }
    uint pixel = uint(screen.y) * params.width + uint(screen.x);
    if (push.depthTolerance > 0.0f) {
        HitPoint hp = hitPoints[pixel];
        float surface = dot(hp.position - params.camera.position, params.camera.forward);
        if (hp.material == NONE || abs(screen.z - surface) > push.depthTolerance * surface) {
            return;
        }
    }
    vec3 value = photon.power * (push.brightness * DOTS_FIXED_POINT);
    atomicAdd(dots[3u * pixel], uint(value.x + 0.5f));
    atomicAdd(dots[3u * pixel + 1u], uint(value.y + 0.5f));
    atomicAdd(dots[3u * pixel + 2u], uint(value.z + 0.5f));
}
