// A daylight sky made on the host as an environment map: Preetham, Shirley & Smits 1999, "A
// Practical Analytic Model for Daylight" (the Perez sky with coefficients linear in turbidity),
// the sun as a disc of its real size seen through the same atmosphere, and a grey ground below
// the horizon lit by both.
//
// Units: linear sRGB radiance [W·sr⁻¹·m⁻²] in the photopic sense: a texel's luminance
// (0.2126 r + 0.7152 g + 0.0722 b) is its luminance in cd/m² divided by 683 lm/W, for the sky and
// for the sun alike, so that sun and sky keep the ratio the model gives them (a clear noon sky is
// a few W·sr⁻¹·m⁻², the sun ~10⁶, the horizontal irradiance of a sunny day ~100 W/m²).
//
// Directions follow shared/environment.h: +Y up, row 0 the zenith, u = 0.5 along −Z.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "core/scene/environment.h"

namespace photon {

struct SkyDesc {
    glm::vec3 sunDirection{0.5f, 0.7071f, 0.5f};  // towards the sun (map space), normalised inside;
                                                 // default 45° high, front right of a default camera
    float turbidity = 3.0f;                        // haze: 2 very clear … 10 hazy (the model's range 1.7–10)
    float groundAlbedo = 0.3f;                     // grey ground below the horizon; 0: a black ground
    std::uint32_t width = 2048, height = 1024;
};

// The sun's angular radius [rad] (0.2667°) and the solid angle of its disc, 2π(1 − cos r) ≈ 6.8e-5 sr.
inline constexpr double kSunAngularRadius = 0.2667 * 3.14159265358979323846 / 180.0;
double sunSolidAngle();

// The map: the sky above the horizon, the sun's disc added to the texels it covers (each by the
// fraction of the texel's solid angle it covers, so the disc's power is the same at every
// resolution), and below the horizon a ground of constant radiance ρ E / π, where E is the
// horizontal irradiance of the sky and sun above it (one bounce off a Lambertian ground of
// albedo ρ; black for ρ = 0). A sun below the horizon shows no disc; the sky is then the model's
// sky for a sun on the horizon, fading linearly to black at −5° elevation (the model holds for
// suns above the horizon only). Throws std::logic_error for a desc the scene loader should have
// refused: turbidity outside [1.7, 10], a zero or non-finite sun direction, an albedo outside
// [0, 1], a size outside 1 … kEnvironmentWidthMax × kEnvironmentHeightMax.
EnvironmentMap makeSkyMap(const SkyDesc& desc);

// The parts of the map, for tests and for lights that want them: the sky alone in the unit map
// direction `toward` (no sun disc; the model continued to the horizon for directions below it),
// and the radiance of the sun's disc, that of its centre's air mass (zero once the disc's top
// edge is below the horizon).
glm::vec3 skyRadiance(const SkyDesc& desc, glm::vec3 toward);
glm::vec3 sunRadiance(const SkyDesc& desc);

}  // namespace photon
