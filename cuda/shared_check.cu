// Compiles every shared header with nvcc, so nothing host-only creeps into shared/.
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

namespace photon {
__global__ void sharedCheck(Bindings bindings) {
    uint i = blockIdx.x * blockDim.x + threadIdx.x;
    tracePhotonPath(bindings, i);
    countPhotonCell(bindings, MAP_GLOBAL, i);
    scatterPhoton(bindings, MAP_GLOBAL, i);
    scatterPhotonId(bindings, MAP_CAUSTIC, i);
    rankInChunk(bindings, MAP_CAUSTIC, i);
    mergeChunks(bindings, MAP_CAUSTIC, i);
    PhotonPath path = startPhotonPath(bindings, i);
    Photon p;
    uint store = photonBounce(bindings, path, p);
    bindings.hitPoints[i] = tracePixel(bindings, i);
    bindings.frameRadiance[i] = vec4(gatherPixel(bindings, i), float(store));
    bindings.accumulation[i] = accumulateMean(bindings.accumulation[i], bindings.frameRadiance[i], bindings.params.accumulated);
    bindings.photonKeys[i] = photonCellKey(p.position, bindings.params.grids[0]);
    bindings.accumulation[i].x += tonemap(vec3(1.0f), 1.0f, TONEMAP_ACES).x + progressiveRadius(1.0f, 0.7f, 3u);
}
}  // namespace photon
