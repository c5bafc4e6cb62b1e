// Error of an image against a converged reference, the way docs/performance.md reports quality:
// relative RMSE over the whole image and outside a window, and inside the window (a caustic's
// focus) the peak and the energy relative to the reference's.
#pragma once

#include <cstdint>

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

}  // namespace photon
