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

namespace {

void checkSizes(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height) {
        throw InputError("the image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                         " and the reference " + std::to_string(reference.width) + "x" +
                         std::to_string(reference.height));
    }
}

double srgb(double linear) {
    double x = std::clamp(linear, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

constexpr int kBlurRadius = 5;

// One pass of the separable blur, along rows or along columns: each pixel becomes the weighted
// mean of the taps of its line that lie inside the image.
void blurPass(const std::vector<double>& in, std::vector<double>& out, std::uint32_t w, std::uint32_t h,
              bool alongColumns, const double (&kernel)[2 * kBlurRadius + 1]) {
    int length = int(alongColumns ? h : w);
    std::size_t step = alongColumns ? w : 1;
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            int at = int(alongColumns ? y : x);
            std::size_t lineStart = std::size_t(y) * w + x - std::size_t(at) * step;
            double sum = 0.0, weights = 0.0;
            for (int i = -kBlurRadius; i <= kBlurRadius; ++i) {
                int q = at + i;
                if (q >= 0 && q < length) {
                    sum += kernel[i + kBlurRadius] * in[lineStart + std::size_t(q) * step];
                    weights += kernel[i + kBlurRadius];
                }
            }
            out[std::size_t(y) * w + x] = sum / weights;
        }
    }
}

// Separable Gaussian blur (σ 1.5, radius 5, normalised over the taps inside: scikit-image filters
// with mode 'reflect' and crops the borders away; here every pixel counts, the border slightly
// differently, which moves SSIM in the fourth decimal on 640×480 images).
std::vector<double> gaussianBlur(const std::vector<double>& in, std::uint32_t w, std::uint32_t h) {
    double kernel[2 * kBlurRadius + 1];
    for (int i = -kBlurRadius; i <= kBlurRadius; ++i) {
        kernel[i + kBlurRadius] = std::exp(-double(i * i) / (2.0 * 1.5 * 1.5));
    }
    std::vector<double> tmp(in.size()), out(in.size());
    blurPass(in, tmp, w, h, false, kernel);
    blurPass(tmp, out, w, h, true, kernel);
    return out;
}

}  // namespace

PixelMask brightestPixels(const Image& reference, double fraction) {
    std::vector<double> l(reference.pixels.size());
    for (std::size_t i = 0; i < l.size(); ++i) {
        l[i] = luminance(reference.pixels[i]);
    }
    std::size_t count = std::max<std::size_t>(1, std::size_t(std::ceil(fraction * double(l.size()))));
    std::vector<double> sorted = l;
    std::nth_element(sorted.begin(), sorted.end() - std::ptrdiff_t(count), sorted.end());
    double threshold = *(sorted.end() - std::ptrdiff_t(count));
    PixelMask mask(l.size());
    for (std::size_t i = 0; i < l.size(); ++i) {
        mask[i] = l[i] >= threshold;
    }
    return mask;
}

PixelMask edgePixels(const Image& reference, double contrast) {
    PixelMask mask(reference.pixels.size(), false);
    for (std::uint32_t y = 0; y < reference.height; ++y) {
        for (std::uint32_t x = 0; x < reference.width; ++x) {
            double l = luminance(reference.at(x, y));
            for (int k = 0; k < 2; ++k) {
                std::uint32_t qx = x + (k == 0 ? 1 : 0), qy = y + (k == 1 ? 1 : 0);
                if (qx >= reference.width || qy >= reference.height) {
                    continue;
                }
                double m = luminance(reference.at(qx, qy));
                if (std::abs(l - m) > contrast * std::max(l, m)) {
                    mask[std::size_t(y) * reference.width + x] = true;
                    mask[std::size_t(qy) * reference.width + qx] = true;
                }
            }
        }
    }
    return mask;
}

PixelMask operator!(const PixelMask& mask) {
    PixelMask inverse(mask.size());
    for (std::size_t i = 0; i < mask.size(); ++i) {
        inverse[i] = !mask[i];
    }
    return inverse;
}

double relativeRmse(const Image& image, const Image& reference, const PixelMask& mask) {
    checkSizes(image, reference);
    double error = 0.0, norm = 0.0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) {
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            double d = double(image.pixels[i][k]) - double(reference.pixels[i][k]);
            error += d * d;
            norm += double(reference.pixels[i][k]) * double(reference.pixels[i][k]);
        }
    }
    return norm > 0.0 ? std::sqrt(error / norm) : std::sqrt(error);
}

double energyRatio(const Image& image, const Image& reference, const PixelMask& mask) {
    checkSizes(image, reference);
    double a = 0.0, r = 0.0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (mask[i]) {
            a += luminance(image.pixels[i]);
            r += luminance(reference.pixels[i]);
        }
    }
    return r > 0.0 ? a / r : 0.0;
}

double peakRatio(const Image& image, const Image& reference, const PixelMask& mask) {
    checkSizes(image, reference);
    double a = 0.0, r = 0.0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (mask[i]) {
            a = std::max(a, luminance(image.pixels[i]));
            r = std::max(r, luminance(reference.pixels[i]));
        }
    }
    return r > 0.0 ? a / r : 0.0;
}

double displaySsim(const Image& image, const Image& reference) {
    checkSizes(image, reference);
    constexpr double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    std::uint32_t w = image.width, h = image.height;
    std::size_t n = image.pixels.size();
    double total = 0.0;
    for (int k = 0; k < 3; ++k) {
        std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
        for (std::size_t i = 0; i < n; ++i) {
            x[i] = srgb(image.pixels[i][k]);
            y[i] = srgb(reference.pixels[i][k]);
            xx[i] = x[i] * x[i];
            yy[i] = y[i] * y[i];
            xy[i] = x[i] * y[i];
        }
        std::vector<double> mx = gaussianBlur(x, w, h), my = gaussianBlur(y, w, h);
        std::vector<double> sxx = gaussianBlur(xx, w, h), syy = gaussianBlur(yy, w, h), sxy = gaussianBlur(xy, w, h);
        double sum = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cxy = sxy[i] - mx[i] * my[i];
            sum += ((2.0 * mx[i] * my[i] + c1) * (2.0 * cxy + c2)) /
                   ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
        }
        total += sum / double(n);
    }
    return total / 3.0;
}

double shareOff(const Image& image, const Image& reference, const PixelMask& mask, double tolerance) {
    checkSizes(image, reference);
    double sum = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (mask[i]) {
            sum += luminance(reference.pixels[i]);
            ++count;
        }
    }
    double floor = count > 0 ? 0.01 * sum / double(count) : 0.0;
    std::size_t lit = 0, off = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        double r = luminance(reference.pixels[i]);
        if (!mask[i] || !(r > floor)) {
            continue;
        }
        ++lit;
        double a = luminance(image.pixels[i]);
        off += !(std::abs(a - r) <= tolerance * r) ? 1 : 0;  // a NaN pixel is off
    }
    return lit > 0 ? double(off) / double(lit) : 0.0;
}

double meanChange(const Image& image, const Image& before) {
    checkSizes(image, before);
    double change = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        double l = luminance(before.pixels[i]);
        change += std::abs(luminance(image.pixels[i]) - l);
        sum += l;
    }
    return sum > 0.0 ? change / sum : change;
}

PixelMask both(const PixelMask& a, const PixelMask& b) {
    PixelMask mask(a.size(), false);
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
        mask[i] = a[i] && b[i];
    }
    return mask;
}

QualityMasks::QualityMasks(const Image& reference, PixelMask glassRegion)
    : focus(brightestPixels(reference, 0.005)), edges(edgePixels(reference, 0.25)), glass(std::move(glassRegion)) {
    if (!glass.empty() && glass.size() != reference.pixels.size()) {
        throw InputError("the glass region has " + std::to_string(glass.size()) + " pixels, the reference " +
                         std::to_string(reference.pixels.size()));
    }
}

Quality measureQuality(const Image& image, const Image& reference, const QualityMasks& masks) {
    Quality q;
    q.whole = relativeRmse(image, reference, PixelMask(reference.pixels.size(), true));
    q.away = relativeRmse(image, reference, !masks.focus);
    q.edges = relativeRmse(image, reference, masks.edges);
    q.focusEnergy = energyRatio(image, reference, masks.focus);
    q.focusPeak = peakRatio(image, reference, masks.focus);
    q.ssim = displaySsim(image, reference);
    if (!masks.glass.empty()) {
        PixelMask glass = both(!masks.focus, masks.glass);
        PixelMask rest = both(!masks.focus, !masks.glass);
        q.glass = relativeRmse(image, reference, glass);
        q.glassOff = shareOff(image, reference, glass, 0.25);
        q.rest = relativeRmse(image, reference, rest);
        q.restOff = shareOff(image, reference, rest, 0.25);
    }
    return q;
}

}  // namespace photon
