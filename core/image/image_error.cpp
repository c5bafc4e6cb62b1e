#include "core/image/image_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/system/error.h"

namespace photon {

double luminance(const glm::vec4& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

Window brightestWindow(const Image& reference, std::uint32_t half) {
    std::uint32_t bx = 0;
    std::uint32_t by = 0;
    double best = -1.0;
    for (std::uint32_t y = 0; y < reference.height; ++y) {
        for (std::uint32_t x = 0; x < reference.width; ++x) {
            double l = luminance(reference.at(x, y));
            if (l > best) {
                best = l;
                bx = x;
                by = y;
            }
        }
    }
    Window w;
    w.x0 = bx > half ? bx - half : 0;
    w.y0 = by > half ? by - half : 0;
    w.x1 = std::min(reference.width, bx + half + 1);
    w.y1 = std::min(reference.height, by + half + 1);
    return w;
}

ImageError compareWithReference(const Image& image, const Image& reference, const Window& window) {
    if (image.width != reference.width || image.height != reference.height) {
        throw InputError("the image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " and the reference " + std::to_string(reference.width) + "x" +
                         std::to_string(reference.height));
    }
    double sq[2] = {0.0, 0.0};   // Σ|a - ref|²: all, outside
    double ref[2] = {0.0, 0.0};  // Σ|ref|²
    double peak[2] = {0.0, 0.0};
    double energy[2] = {0.0, 0.0};
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const glm::vec4& a = image.at(x, y);
            const glm::vec4& r = reference.at(x, y);
            double d2 = 0.0;
            double r2 = 0.0;
            for (int k = 0; k < 3; ++k) {
                d2 += (double(a[k]) - double(r[k])) * (double(a[k]) - double(r[k]));
                r2 += double(r[k]) * double(r[k]);
            }
            bool in = window.contains(x, y);
            sq[0] += d2;
            ref[0] += r2;
            if (!in) {
                sq[1] += d2;
                ref[1] += r2;
            } else {
                peak[0] = std::max(peak[0], luminance(a));
                peak[1] = std::max(peak[1], luminance(r));
                energy[0] += luminance(a);
                energy[1] += luminance(r);
            }
        }
    }
    auto relative = [](double num, double den) { return den > 0.0 ? std::sqrt(num / den) : std::sqrt(num); };
    ImageError e;
    e.whole = relative(sq[0], ref[0]);
    e.outside = relative(sq[1], ref[1]);
    e.peakRatio = peak[1] > 0.0 ? peak[0] / peak[1] : 0.0;
    e.energyRatio = energy[1] > 0.0 ? energy[0] / energy[1] : 0.0;
    return e;
}

}  // namespace photon
