#include "core/image/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <tinyexr.h>

#include "core/image/display_bytes.h"
#include "core/image/exr_writer.h"
#include "core/image/png_writer.h"
#include "core/system/error.h"
#include "core/system/numbers.h"
#include "core/system/output_file.h"

namespace photon {
namespace {

std::string lowerExtension(const std::string& path) {
    auto dot = path.find_last_of('.');
    if (dot == std::string::npos) {
        return "";
    }
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string encodeDisplayPng(const Image& image, float exposure, Tonemap curve) {
    float scale = std::exp2(exposure);
    return encodePng(image.width, image.height, [&](std::uint32_t y, unsigned char* rgb) {
        displayBytes(&image.pixels[std::size_t(y) * image.width], image.width, scale, curve, rgb);
    });
}

// Portable float map: "PF", size, scale (negative: little-endian), rows bottom to top.
std::string encodePfm(const Image& image) {
    std::string bytes = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    bytes.reserve(bytes.size() + image.pixels.size() * 3 * sizeof(float));
    std::vector<float> row(std::size_t(image.width) * 3);
    for (std::uint32_t y = image.height; y-- > 0;) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            for (int k = 0; k < 3; ++k) {
                row[3 * x + k] = image.at(x, y)[k];
            }
        }
        bytes.append(reinterpret_cast<const char*>(row.data()), row.size() * sizeof(float));
    }
    return bytes;
}

Image readPfm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw InputError(path + ": cannot open file");
    }
    std::string magic;
    long w = 0;
    long h = 0;
    float scale = 0.0f;
    in >> magic >> w >> h >> scale;
    in.get();
    if (magic != "PF" || w <= 0 || h <= 0 || w > 65536 || h > 65536 || scale >= 0.0f) {
        throw InputError(path + ": not a little-endian RGB PFM file");
    }
    Image image{std::uint32_t(w), std::uint32_t(h)};
    std::vector<float> row(std::size_t(w) * 3);
    for (long y = h; y-- > 0;) {
        in.read(reinterpret_cast<char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
        for (long x = 0; x < w; ++x) {
            image.at(std::uint32_t(x), std::uint32_t(y)) = glm::vec4(row[3 * x], row[3 * x + 1], row[3 * x + 2], 1.0f);
        }
    }
    if (!in) {
        throw InputError(path + ": truncated PFM file");
    }
    return image;
}

Image readExr(const std::string& path) {
    float* rgba = nullptr;
    int w = 0;
    int h = 0;
    const char* err = nullptr;
    if (LoadEXR(&rgba, &w, &h, path.c_str(), &err) != TINYEXR_SUCCESS) {
        std::string reason = err ? err : "unknown error";
        FreeEXRErrorMessage(err);
        throw InputError(path + ": cannot read EXR: " + reason);
    }
    Image image{std::uint32_t(w), std::uint32_t(h)};
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], 1.0f);
    }
    std::free(rgba);
    return image;
}

}  // namespace

ImageFormat imageFormatFor(const std::string& path) {
    if (path.empty()) {
        throw InputError("the image path is empty (name a .png, .exr or .pfm file)");
    }
    std::string ext = lowerExtension(path);
    if (ext == "png") {
        return ImageFormat::Png;
    }
    if (ext == "exr") {
        return ImageFormat::Exr;
    }
    if (ext == "pfm") {
        return ImageFormat::Pfm;
    }
    throw InputError(path + ": unknown image format (use .png, .exr or .pfm)");
}

std::string encodeImage(ImageFormat format, const Image& image, float exposure, Tonemap curve,
                        const std::vector<ExrLayer>& layers) {
    switch (format) {
        case ImageFormat::Png: return encodeDisplayPng(image, exposure, curve);
        case ImageFormat::Exr: return encodeExr(image, ExrCompression::Rle, ExrLayout::Scanlines, layers);
        case ImageFormat::Pfm: return encodePfm(image);
    }
    return {};
}

void writeImage(const std::string& path, const Image& image, float exposure, Tonemap curve,
                const std::vector<ExrLayer>& layers) {
    ImageFormat format = imageFormatFor(path);
    bool finite = allFinite(image);
    for (const ExrLayer& layer : layers) {
        finite = finite && (format != ImageFormat::Exr || allFinite(*layer.image));
    }
    if (!finite) {
        throw RuntimeError(path + ": the image holds values that are not finite; nothing was written");
    }
    std::string bytes;
    try {
        bytes = encodeImage(format, image, exposure, curve, layers);
    } catch (const RuntimeError& e) {
        throw RuntimeError(path + ": " + e.what());
    }
    writeOutputFile(path, bytes, "image");
}

void writeRgb8Png(const std::string& path, const unsigned char* rgb, std::uint32_t width, std::uint32_t height) {
    std::size_t stride = std::size_t(width) * 3;
    std::string png;
    try {
        png = encodePng(width, height, [&](std::uint32_t y, unsigned char* row) {
            std::memcpy(row, rgb + stride * y, stride);
        });
    } catch (const RuntimeError& e) {
        throw RuntimeError(path + ": " + e.what());
    }
    writeOutputFile(path, png, "image");
}

Image readImage(const std::string& path) {
    switch (imageFormatFor(path)) {
        case ImageFormat::Exr:
            return readExr(path);
        case ImageFormat::Pfm:
            return readPfm(path);
        default:
            throw InputError(path + ": only .exr and .pfm images can be read");
    }
}

double relativeRmse(const Image& a, const Image& reference) {
    if (a.width != reference.width || a.height != reference.height) {
        return INFINITY;
    }
    double num = 0.0;
    double den = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        for (int k = 0; k < 3; ++k) {
            double d = double(a.pixels[i][k]) - double(reference.pixels[i][k]);
            num += d * d;
            den += double(reference.pixels[i][k]) * double(reference.pixels[i][k]);
        }
    }
    return den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
}

double meanLuminance(const Image& image) {
    double sum = 0.0;
    for (const glm::vec4& p : image.pixels) {
        sum += 0.2126 * p.x + 0.7152 * p.y + 0.0722 * p.z;
    }
    return image.pixels.empty() ? 0.0 : sum / double(image.pixels.size());
}

double litFraction(const Image& image, float exposure) {
    float threshold = kLitRadiance / std::exp2(exposure);
    auto lit = std::count_if(image.pixels.begin(), image.pixels.end(),
                             [&](const glm::vec4& p) { return std::max({p.x, p.y, p.z}) >= threshold; });
    return image.pixels.empty() ? 0.0 : double(lit) / double(image.pixels.size());
}

std::string nearlyBlackWarning(const Image& image, float exposure, const std::string& source) {
    double lit = litFraction(image, exposure);
    if (lit >= kNearBlackFraction) {
        return "";
    }
    char share[32];
    std::snprintf(share, sizeof share, "%.1f%%", 100.0 * lit);
    return source + ": the image is nearly black: " + share + " of its pixels show (at --exposure " + formatNumber(exposure) +
           "); do the lights reach what the camera sees?";
}

bool allFinite(const Image& image) {
    return std::all_of(image.pixels.begin(), image.pixels.end(), [](const glm::vec4& p) {
        return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    });
}

Image differenceImage(const Image& a, const Image& b) {
    Image d(a.width, a.height);
    float largest = 0.0f;
    for (std::size_t i = 0; i < d.pixels.size() && i < b.pixels.size(); ++i) {
        d.pixels[i] = glm::abs(a.pixels[i] - b.pixels[i]);
        largest = std::max({largest, d.pixels[i].x, d.pixels[i].y, d.pixels[i].z});
    }
    for (glm::vec4& p : d.pixels) {
        p = largest > 0.0f ? p / largest : p;
        p.w = 1.0f;
    }
    return d;
}

}  // namespace photon
