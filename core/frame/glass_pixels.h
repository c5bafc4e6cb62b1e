// The glass region of an image: the pixels whose camera ray, through the pixel's centre, first meets
// a surface that transmits (glass, or a glTF material with transmission). Where a photon mapper's
// eye paths split or choose, and where issue 58's error is measured apart (photon-converge).
#pragma once

#include <vector>

#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon {

// One entry per pixel, row by row, at the settings' width and height.
std::vector<bool> glassPixels(const Scene& scene, const CameraDesc& camera, const RenderSettings& settings);

}  // namespace photon
