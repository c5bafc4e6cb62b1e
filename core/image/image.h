// Linear RGB images and their files: PNG (tone-mapped sRGB), OpenEXR and PFM (linear radiance).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/settings/settings.h"

namespace photon {

struct Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec4> pixels;  // row-major from the top; rgb = radiance, a unused

    Image() = default;
    Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), pixels(std::size_t(w) * h, glm::vec4(0.0f)) {}
    glm::vec4& at(std::uint32_t x, std::uint32_t y) { return pixels[std::size_t(y) * width + x]; }
    const glm::vec4& at(std::uint32_t x, std::uint32_t y) const { return pixels[std::size_t(y) * width + x]; }
};

enum class ImageFormat { Png, Exr, Pfm };

// A further image in an EXR file, as channels "<name>.<channel>" (OpenEXR's layer naming):
// channel i is component i of the image's pixels ("RGB", "XYZ" for a normal, "Z" for depth).
struct ExrLayer {
    std::string name;
    const Image* image = nullptr;  // the main image's size
    std::string channels;          // one letter a channel, at most four
};

// The format for a file name's extension; throws InputError for anything else.
ImageFormat imageFormatFor(const std::string& path);

// The file's bytes, in memory. Throws RuntimeError if an encoder fails.
std::string encodeImage(ImageFormat format, const Image& image, float exposure, Tonemap tonemap,
                        const std::vector<ExrLayer>& layers = {});

// Writes by extension, whole or not at all (core/system/output_file.h). PNG applies exposure (stops) and
// the tone curve; EXR and PFM are linear (core/image/png_writer.h, exr_writer.h say how). Throws
// RuntimeError "<path>: <reason>" if the image cannot be encoded or the file cannot be written
// (with the OS's reason). EXR files get the layers too; the other formats only the image.
void writeImage(const std::string& path, const Image& image, float exposure, Tonemap tonemap,
                const std::vector<ExrLayer>& layers = {});

// An 8-bit RGB picture (display values) as PNG, whole or not at all.
void writeRgb8Png(const std::string& path, const unsigned char* rgb, std::uint32_t width, std::uint32_t height);

// Reads a PFM or EXR file (linear); throws InputError.
Image readImage(const std::string& path);

// Relative RMSE of a against the reference: sqrt(Σ|a-ref|²) / sqrt(Σ|ref|²) over rgb.
double relativeRmse(const Image& a, const Image& reference);
double meanLuminance(const Image& image);
bool allFinite(const Image& image);
// The share of pixels that show: max(r, g, b) · 2^exposure at least kLitRadiance (about 10% grey
// once sRGB-encoded). Below kNearBlackFraction the programs warn that the image is nearly black.
inline constexpr float kLitRadiance = 0.01f;
inline constexpr double kNearBlackFraction = 0.1;
double litFraction(const Image& image, float exposure);
// "<source>: the image is nearly black: 2.1% of its pixels show (at --exposure 0); do the lights
// reach what the camera sees?", or empty where the image shows.
std::string nearlyBlackWarning(const Image& image, float exposure, const std::string& source);
// |a - b| scaled so that the largest difference is 1, for looking at.
Image differenceImage(const Image& a, const Image& b);

}  // namespace photon
