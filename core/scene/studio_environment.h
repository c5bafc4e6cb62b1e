// A neutral studio environment for lighting models on their own, as glTF viewers do: grey
// everywhere (r = g = b, no colour cast), a soft backdrop and three rectangular soft boxes.
//
// Layout, in shared/environment.h's map directions (+Y up; azimuth φ from −Z, where a default
// camera looks and the map's centre column lies, towards +X; "front" is +Z, the camera's side;
// elevation above the horizon):
//   backdrop  radiance 0.5 + 0.3 cos θ above the horizon (0.8 at the zenith, 0.5 at the horizon),
//             a floor of 0.15 below it, the two blended over ±2° of elevation;
//   key       front left above: centre at elevation 45°, φ = −135° (towards −X and +Z),
//             60° wide × 40° high, relative radiance 1;
//   fill      front right, lower and dimmer: elevation 20°, φ = +120° (towards +X and +Z),
//             50° × 35°, relative radiance 0.35;
//   rim       behind the model, high (out of a default view): elevation 45°, φ = +20° (towards −Z,
//             a little +X), a strip 15° wide × 40° high, relative radiance 0.6.
// Each box is a flat rectangle facing the origin (its sides horizontal and tilted-vertical),
// seen from the origin as `wide × high` degrees, with edges that fade over ±0.1 of its tangent
// plane (about ±6° at the centre). The boxes add to the backdrop; their scale (relative radiance
// 1 is ~1.6 W·sr⁻¹·m⁻², so the key is ~2.3 in all) is set so that the irradiance of a surface
// facing up is π W/m² on the map itself: a white Lambertian surface facing up has radiance 1.
#pragma once

#include <cstdint>

#include "core/scene/environment.h"

namespace photon {

// Throws std::logic_error for a size outside 1 … kEnvironmentWidthMax × kEnvironmentHeightMax.
EnvironmentMap makeStudioMap(std::uint32_t width = 1024, std::uint32_t height = 512);

}  // namespace photon
