#include "texture_loader.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <stb_image.h>

#include "error.h"
#include "shared/texture.h"

namespace photon {
namespace {

// sRGB transfer function, inverted.
double linearFromSrgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

std::uint32_t quantize(double linear) { return std::uint32_t(std::lround(std::clamp(linear, 0.0, 1.0) * 65535.0)); }

}  // namespace

std::uint32_t addImageTexture(Scene& scene, const std::string& bytes, std::uint32_t wrapS, std::uint32_t wrapT,
                              const std::string& where, TextureEncoding encoding) {
    auto decode = [encoding](double c) { return encoding == TextureEncoding::Srgb ? linearFromSrgb(c) : c; };
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    if (bytes.size() > std::size_t(1) << 30) {
        throw InputError(where + ": image data over 1 GiB");
    }
    int size = int(bytes.size());
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!stbi_info_from_memory(data, size, &width, &height, &channels)) {
        throw InputError(where + ": not an image Photon reads (PNG or JPEG): " +
                         (stbi_failure_reason() ? stbi_failure_reason() : "unknown format"));
    }
    if (width < 1 || height < 1 || width > int(TEXTURE_SIZE_MAX) || height > int(TEXTURE_SIZE_MAX)) {
        throw InputError(where + ": image of " + std::to_string(width) + "x" + std::to_string(height) +
                         " texels; at most " + std::to_string(TEXTURE_SIZE_MAX) + " a side");
    }
    bool sixteen = stbi_is_16_bit_from_memory(data, size) != 0;
    std::vector<glm::uvec2> texels(std::size_t(width) * std::size_t(height));
    int w = 0;
    int h = 0;
    int n = 0;
    if (sixteen) {
        std::unique_ptr<stbi_us, void (*)(void*)> pixels(stbi_load_16_from_memory(data, size, &w, &h, &n, 4), stbi_image_free);
        if (!pixels || w != width || h != height) {
            throw InputError(where + ": cannot decode the image: " + (stbi_failure_reason() ? stbi_failure_reason() : "?"));
        }
        for (std::size_t i = 0; i < texels.size(); ++i) {
            std::uint32_t c[4];
            for (int k = 0; k < 3; ++k) {
                c[k] = quantize(decode(pixels.get()[4 * i + k] / 65535.0));
            }
            c[3] = pixels.get()[4 * i + 3];
            texels[i] = glm::uvec2(c[0] | (c[1] << 16), c[2] | (c[3] << 16));
        }
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, size, &w, &h, &n, 4), stbi_image_free);
        if (!pixels || w != width || h != height) {
            throw InputError(where + ": cannot decode the image: " + (stbi_failure_reason() ? stbi_failure_reason() : "?"));
        }
        std::uint32_t table[256];
        for (int v = 0; v < 256; ++v) {
            table[v] = quantize(decode(v / 255.0));
        }
        for (std::size_t i = 0; i < texels.size(); ++i) {
            const stbi_uc* p = pixels.get() + 4 * i;
            texels[i] = glm::uvec2(table[p[0]] | (table[p[1]] << 16), table[p[2]] | (std::uint32_t(p[3]) * 257u << 16));
        }
    }
    return scene.addTexture(std::uint32_t(width), std::uint32_t(height), std::move(texels), wrapS, wrapT);
}

}  // namespace photon
