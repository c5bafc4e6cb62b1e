// Automatic query radii that know the image: a pixel's footprint (its width at its visible point,
// shared/sppm.h pixelFootprint) measured over a sparse grid of pixel centres, traced on the host
// with the shared eye pass. A radius of a few footprints blurs a few pixels wherever the camera
// looks, whatever the scene's extent (an object far outside the view changes nothing).
#pragma once

#include <cstdint>

#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon {

struct Footprints {
    float median = 0.0f;  // over the sampled pixels whose eye path ended on a surface
    float high = 0.0f;    // the 90th percentile
    bool any = false;     // some sampled eye path ended on a surface
};

// Traces up to 48 × 36 pixel centres of the image.
Footprints measureFootprints(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings);

}  // namespace photon
