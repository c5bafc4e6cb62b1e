// What spectral rendering needs on the host (shared/spectral.h runs it): the CIE 1931 observer,
// the visible-wavelength distribution paths draw from, the spectral primaries that lift RGB to
// spectra, the dispersion law, and each frame's wavelength set.
#pragma once

#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "shared/layout.h"

namespace photon {

inline constexpr double kVisibleMin = 360.0;  // nm: the range paths sample
inline constexpr double kVisibleMax = 830.0;

// x̄, ȳ, z̄ of the CIE 1931 2° observer: Wyman, Sloan & Shirley's multi-lobe fit (JCGT 2013).
glm::dvec3 cie1931(double lambda);

// λ ∈ [360, 830] nm from u ∈ [0, 1), with a density proportional to |r̄| + |ḡ| + |b̄|, the
// observer's linear sRGB matching functions (tabulated at 1 nm, uniform within each), and that
// density. Against pbrt-v4's SampleVisibleWavelengths (a density close to ȳ's), a flat spectrum
// seen through the frames' wavelength sets is 2.6× closer to white after one frame, 2.1× after
// four and 4.2× after sixteen (tools/wavelength_sampling.py): ȳ's density starves the blue channel.
double sampleVisibleWavelength(double u);
double visibleWavelengthPdf(double lambda);

// Linear sRGB of an XYZ colour, white-balanced so that the flat (equal-energy) spectrum is
// (1, 1, 1): an RGB white lifts to the flat spectrum and comes back white.
glm::dvec3 rgbFromXyz(const glm::dvec3& xyz);

// Three spectra r(λ), g(λ), b(λ), each in [0, 1], summing to 1 at every wavelength, whose
// colours are exactly the sRGB primaries: the smoothest such (Mallett & Yuksel 2019, "Spectral
// Primary Decomposition for Rendering with sRGB Reflectance"), solved once, on a 10 nm grid. An
// RGB reflectance in [0, 1]³ lifts to r·R(λ) + g·G(λ) + b·B(λ), a reflectance in [0, 1] with the
// same colour; white lifts to 1.
struct SpectralPrimaries {
    static constexpr double kStep = 10.0;
    static constexpr int kCount = 48;  // 360, 370, ..., 830 nm
    std::array<glm::dvec3, kCount> values{};

    glm::dvec3 at(double lambda) const;  // linear between the grid's wavelengths
};
const SpectralPrimaries& spectralPrimaries();

// The refractive index at λ [nm] of a material with index n_d (at 587.6 nm) and dispersion
// 20 / V_d (KHR_materials_dispersion).
double dispersedIor(double ior, double dispersion, double lambda);

// The frame's wavelengths and conversions (layout.h, SpectralParams): drawn for frame
// `frameIndex`, or every one at `fixedWavelength` [nm] when that is not 0 (then the image shows
// the radiance at that wavelength as grey, as a monochrome sensor behind a narrow filter would).
SpectralParams frameSpectrum(std::uint32_t frameIndex, std::uint32_t seed, float fixedWavelength);

}  // namespace photon
