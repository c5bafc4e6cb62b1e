// The auxiliary images a render keeps (shared/aov.h) as images: for EXR layers, the viewer's
// views and the tests.
#pragma once

#include <cstdint>
#include <vector>

#include "core/image/image.h"
#include "shared/layout.h"

namespace photon {

struct AovImages {
    Image albedo;    // rgb: reflectance where the eye paths ended, after mirrors and glass
    Image normal;    // xyz: mean shading normal, 0 where paths escaped
    Image depth;     // x: mean length of the eye path to the surface it ended on (through mirrors and glass), 0: none
    Image variance;  // x: variance of the image's luminance (of the mean of `frames` frames, from their moments)
};

// From a readback of the AOV buffer (Renderer::readAovs()) of a width × height image of `frames` frames.
AovImages aovImages(const std::vector<PixelAov>& aovs, std::uint32_t width, std::uint32_t height, std::uint32_t frames);

// The layers of an EXR file that hold them: albedo.RGB, normal.XYZ, depth.Z, variance.Y.
std::vector<ExrLayer> exrLayers(const AovImages& images);

}  // namespace photon
