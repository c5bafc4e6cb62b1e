#include "core/frame/aov_images.h"

#include <algorithm>
#include <stdexcept>

namespace photon {

AovImages aovImages(const std::vector<PixelAov>& aovs, std::uint32_t width, std::uint32_t height, std::uint32_t frames) {
    if (aovs.size() != std::size_t(width) * height) {
        throw std::invalid_argument("aovImages: the readback is not width x height");
    }
    AovImages images{Image(width, height), Image(width, height), Image(width, height), Image(width, height)};
    float n = float(std::max(frames, 1u));
    for (std::size_t i = 0; i < aovs.size(); ++i) {
        const PixelAov& a = aovs[i];
        images.albedo.pixels[i] = glm::vec4(a.albedo, 1.0f);
        images.normal.pixels[i] = glm::vec4(a.normal, 0.0f);
        images.depth.pixels[i] = glm::vec4(a.coverage > 0.0f ? a.depth : 0.0f, 0.0f, 0.0f, 0.0f);
        float variance = std::max(a.luminance2 - a.luminance * a.luminance, 0.0f) / n;
        images.variance.pixels[i] = glm::vec4(variance, 0.0f, 0.0f, 0.0f);
    }
    return images;
}

std::vector<ExrLayer> exrLayers(const AovImages& images) {
    return {{"albedo", &images.albedo, "RGB"},
            {"normal", &images.normal, "XYZ"},
            {"depth", &images.depth, "Z"},
            {"variance", &images.variance, "Y"}};
}

}  // namespace photon
