#include "core/loaders/texture_loader.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <stb_image.h>

#include "core/system/error.h"
#include "shared/texture.h"

namespace photon {
namespace {

// sRGB transfer function, inverted.
double linearFromSrgb(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

std::uint32_t quantize(double linear) { return std::uint32_t(std::lround(std::clamp(linear, 0.0, 1.0) * 65535.0)); }

std::uint32_t bigEndian(const std::string& b, std::size_t at, int bytes) {
    std::uint32_t x = 0;
    for (int i = 0; i < bytes; ++i) {
        x = (x << 8) | static_cast<unsigned char>(b[at + std::size_t(i)]);
    }
    return x;
}

// The size a PNG or JPEG header announces, read here because stb_image gives up on images too
// large for it with "unknown image type". False if the header does not say.
bool announcedSize(const std::string& b, std::uint32_t& width, std::uint32_t& height) {
    // PNG: the signature, then the IHDR chunk: width and height, 4 bytes each.
    if (b.size() >= 24 && b.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 && b.compare(12, 4, "IHDR") == 0) {
        width = bigEndian(b, 16, 4);
        height = bigEndian(b, 20, 4);
        return true;
    }
    // JPEG: markers from SOI up to a start of frame (SOF0 … SOF15 but DHT, JPG and DAC), whose
    // segment holds the precision, then height and width, 2 bytes each.
    if (b.size() < 4 || static_cast<unsigned char>(b[0]) != 0xff || static_cast<unsigned char>(b[1]) != 0xd8) {
        return false;
    }
    for (std::size_t at = 2; at + 9 <= b.size();) {
        if (static_cast<unsigned char>(b[at]) != 0xff) {
            return false;
        }
        auto marker = static_cast<unsigned char>(b[at + 1]);
        if (marker == 0xff) {
            at += 1;  // a fill byte before a marker
            continue;
        }
        if (marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc) {
            height = bigEndian(b, at + 5, 2);
            width = bigEndian(b, at + 7, 2);
            return true;
        }
        at += 2 + bigEndian(b, at + 2, 2);
    }
    return false;
}

}  // namespace

std::uint32_t addImageTexture(Scene& scene, const std::string& bytes, std::uint32_t wrapS, std::uint32_t wrapT,
                              const std::string& where, TextureEncoding encoding) {
    auto decode = [encoding](double c) { return encoding == TextureEncoding::Srgb ? linearFromSrgb(c) : c; };
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    if (bytes.size() > std::size_t(1) << 30) {
        throw InputError(where + ": image data over 1 GiB");
    }
    int size = int(bytes.size());
    auto tooLarge = [&](std::uint64_t w, std::uint64_t h) {
        return InputError(where + ": image of " + std::to_string(w) + "x" + std::to_string(h) + " texels; at most " +
                          std::to_string(TEXTURE_SIZE_MAX) + " a side");
    };
    std::uint32_t announcedWidth = 0;
    std::uint32_t announcedHeight = 0;
    if (announcedSize(bytes, announcedWidth, announcedHeight) &&
        (announcedWidth > TEXTURE_SIZE_MAX || announcedHeight > TEXTURE_SIZE_MAX)) {
        throw tooLarge(announcedWidth, announcedHeight);
    }
    int width = 0;
    int height = 0;
    int channels = 0;
    if (!stbi_info_from_memory(data, size, &width, &height, &channels)) {
        throw InputError(where + ": not an image Photon reads (PNG or JPEG): " +
                         (stbi_failure_reason() ? stbi_failure_reason() : "unknown format"));
    }
    if (width < 1 || height < 1 || width > int(TEXTURE_SIZE_MAX) || height > int(TEXTURE_SIZE_MAX)) {
        throw tooLarge(std::uint64_t(std::max(width, 0)), std::uint64_t(std::max(height, 0)));
    }
    bool sixteen = stbi_is_16_bit_from_memory(data, size) != 0;
    // stb_image converts 16-bit PNM and PSD images to four channels with its 8-bit converter, into
    // a buffer half the size it then reads (found by fuzzing). 16-bit images are read from PNG only.
    bool png = bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) == 0;
    if (sixteen && !png) {
        throw InputError(where + ": a 16-bit image that is not a PNG; Photon reads 16 bits a channel from PNG only "
                                 "(save it with 8 bits a channel, or as a PNG)");
    }
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
