// The settings against the scene they render: what can only be chosen or checked once the scene
// is known (settings/ itself knows no scene).
#pragma once

#include "core/frame/estimator_policy.h"
#include "core/scene/scene.h"
#include "core/settings/settings.h"

namespace photon {

// Spectral rendering when neither the file nor the command line says: on for a scene with a
// dispersive material (an Abbe number, KHR_materials_dispersion), which RGB cannot show; else RGB
// (spectral's first frames carry a colour cast; docs/performance.md, issue 21).
void chooseSpectral(RenderSettings& settings, const Scene& scene);

// Query radii the grids can hold; an automatic radius out of range blames the scene's extent.
void validateForScene(const RenderSettings& settings, const Scene& scene, const FrameRadii& radii);

}  // namespace photon
