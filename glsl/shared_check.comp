#version 460
// Compiles every shared header as GLSL, so nothing C++-only creeps into shared/.
#extension GL_GOOGLE_include_directive : require
#include "../shared/aov.h"
#include "../shared/bindings.h"
#include "../shared/bsdf.h"
#include "../shared/constants.h"
#include "../shared/denoise.h"
#include "../shared/dispersion.h"
#include "../shared/environment.h"
#include "../shared/estimate.h"
#include "../shared/eye_trace.h"
#include "../shared/gather.h"
#include "../shared/grid.h"
#include "../shared/history.h"
#include "../shared/intersect.h"
#include "../shared/layout.h"
#include "../shared/light_types.h"
#include "../shared/map_photon.h"
#include "../shared/medium.h"
#include "../shared/medium_grid.h"
#include "../shared/light_sources.h"
#include "../shared/emission.h"
#include "../shared/caustic_aiming.h"
#include "../shared/direct_light.h"
#include "../shared/lights.h"
#include "../shared/material.h"
#include "../shared/math.h"
#include "../shared/microfacet.h"
#include "../shared/pbr.h"
#include "../shared/photon_map.h"
#include "../shared/photon_trace.h"
#include "../shared/portable.h"
#include "../shared/progressive.h"
#include "../shared/reproject.h"
#include "../shared/rng.h"
#include "../shared/sampling.h"
#include "../shared/specular_split.h"
#include "../shared/spectral.h"
#include "../shared/sppm.h"
#include "../shared/stages.h"
#include "../shared/surface.h"
#include "../shared/texture.h"
#include "../shared/tonemap.h"
#include "../shared/volume_estimate.h"
#include "../shared/wide_box_test_simd.h"

layout(local_size_x = 64) in;

void main() {
    uint i = gl_GlobalInvocationID.x;
    tracePhotonPath(i);
    traceSharedPhotonPath(i);
    countPhotonCell(MAP_GLOBAL, i);
    scatterPhoton(MAP_GLOBAL, i);
    scatterPhotonId(MAP_CAUSTIC, i);
    rankInChunk(MAP_CAUSTIC, i);
    mergeChunks(MAP_CAUSTIC, i);
    PhotonPath path = startPhotonPath(i);
    Photon p;
    uint store = photonBounce(path, p);
    hitPoints[i] = tracePixel(i);
    frameRadiance[i] = vec4(gatherPixel(i) + vec3(gatherStage(i, ESTIMATOR_SPPM, GLOBAL_DIRECT, true)), float(store));
    accumulation[i] = accumulatePixel(i);
    accumulation[i] = accumulateMean(accumulation[i], frameRadiance[i], params.accumulated);
    photonKeys[i] = photonCellKey(p.position, params.grids[0]);
    accumulation[i].x += tonemap(vec3(1.0f), 1.0f, TONEMAP_ACES).x + progressiveRadius(1.0f, 0.7f, 3u);
}
