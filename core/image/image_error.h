// Error of an image against a converged reference, the way docs/performance.md reports quality:
// relative RMSE over the whole image and outside a window, and inside the window (a caustic's
// focus) the peak and the energy relative to the reference's.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image/image.h"

namespace photon {

// Pixels [x0, x1) × [y0, y1).
struct Window {
    std::uint32_t x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    bool contains(std::uint32_t x, std::uint32_t y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// The (2·half + 1)² window about the reference's brightest pixel (by luminance), clipped to it.
Window brightestWindow(const Image& reference, std::uint32_t half);

struct ImageError {
    double whole = 0.0;        // relative RMSE, every pixel
    double outside = 0.0;      // relative RMSE of the pixels outside the window
    double peakRatio = 0.0;    // largest luminance in the window / the reference's there
    double energyRatio = 0.0;  // Σ luminance in the window / the reference's there
};

// Throws InputError if the sizes differ.
ImageError compareWithReference(const Image& image, const Image& reference, const Window& window);

double luminance(const glm::vec4& rgb);

// Pixels of a reference image, for measuring an error in part of it.
using PixelMask = std::vector<bool>;

// The reference's brightest `fraction` of pixels by luminance: a caustic's focus, highlights.
PixelMask brightestPixels(const Image& reference, double fraction);
// Pixels whose luminance differs from a 4-neighbour's by more than `contrast` times the larger of
// the two: the reference's edges (silhouettes, shadow boundaries, texture edges).
PixelMask edgePixels(const Image& reference, double contrast);
PixelMask operator!(const PixelMask& mask);

// Relative RMSE over the pixels of the mask.
double relativeRmse(const Image& image, const Image& reference, const PixelMask& mask);
// Σ luminance over the mask / the reference's there, and the largest luminance there / the reference's.
double energyRatio(const Image& image, const Image& reference, const PixelMask& mask);
double peakRatio(const Image& image, const Image& reference, const PixelMask& mask);
// The share of the mask's pixels whose luminance is off the reference's by more than `tolerance`
// of it: specks, as the eye sees them. Pixels darker than 1% of the mask's mean reference
// luminance are left out (a relative error of black means nothing).
double shareOff(const Image& image, const Image& reference, const PixelMask& mask, double tolerance);
PixelMask both(const PixelMask& a, const PixelMask& b);
// Σ |L(image) - L(before)| / Σ L(before) over every pixel: how much an image changed from the one
// before it (a still camera's flicker, frame to frame).
double meanChange(const Image& image, const Image& before);

// The structural similarity (Wang et al. 2004) of the two images' display values (linear radiance
// clamped to [0, 1] through the sRGB curve), as scikit-image's structural_similarity computes it
// with gaussian_weights=True (σ 1.5, an 11 × 11 window, K1 0.01, K2 0.03, population covariances,
// data range 1): the mean over the pixels of each channel, averaged over the channels.
double displaySsim(const Image& image, const Image& reference);

// Quality as issue 37 reports it: the whole image, away from the focus (outside the reference's
// brightest 0.5%), at the edges, the focus's energy and peak, and SSIM; and as issue 58 does, where
// a glass region is given (core/frame/glass_pixels.h): the error away from the focus split into
// the glass region and the rest, each with its share of pixels off by more than 25%.
struct Quality {
    double whole = 0.0, away = 0.0, edges = 0.0, focusEnergy = 0.0, focusPeak = 0.0, ssim = 0.0;
    double glass = 0.0, glassOff = 0.0;  // in the glass region, away from the focus (0 without one)
    double rest = 0.0, restOff = 0.0;    // away from the focus and outside the glass region
};
struct QualityMasks {
    PixelMask focus;  // brightestPixels(reference, 0.005)
    PixelMask edges;  // edgePixels(reference, 0.25)
    PixelMask glass;  // empty: none given
    explicit QualityMasks(const Image& reference, PixelMask glassRegion = {});
};
Quality measureQuality(const Image& image, const Image& reference, const QualityMasks& masks);

}  // namespace photon
