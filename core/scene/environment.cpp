#include "core/scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "core/system/host_memory.h"
#include "core/system/parallel.h"
#include "shared/environment.h"

namespace photon {

std::uint32_t encodeRgbe(glm::vec3 c) {
    float v = std::max(c.x, std::max(c.y, c.z));
    if (!(v >= 1e-32f)) {
        return 0u;
    }
    // v = m · 2^e with m in [0.5, 1) (frexp's convention), read from v's bits: e is at most 128
    // for a finite float and at least −106 above 1e-32, so 2^(8 − e) is a normal float too.
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    int e = std::min(int((bits >> 23) & 255u) - 126, 127);  // (2^127 and above: the largest RGBE value)
    std::uint32_t scaleBits = std::uint32_t(127 + 8 - e) << 23;
    float scale;
    std::memcpy(&scale, &scaleBits, sizeof scale);  // 256 / 2^e: the largest channel in [128, 256)
    auto channel = [&](float x) { return std::min(std::uint32_t(x * scale), 255u); };
    return channel(c.x) | channel(c.y) << 8 | channel(c.z) << 16 | std::uint32_t(e + 128) << 24;
}

EnvironmentDistribution buildEnvironmentDistribution(const EnvironmentMap& map) {
    EnvironmentDistribution d;
    std::size_t w = map.width;
    std::size_t h = map.height;
    if (h == 0) {
        return d;
    }
    // The two arrays' zero fill (and first page faults, in huge pages) side by side: for a
    // 4096 × 2048 map, 66 MB that a single thread takes a third of the build for.
    d.texels.reserve(w * h);
    d.cdf.reserve((h + 1) + h * (w + 1));
    adviseHugePages(d.texels.data(), d.texels.capacity() * sizeof(std::uint32_t));
    adviseHugePages(d.cdf.data(), d.cdf.capacity() * sizeof(float));
    parallelFor(2, 1, [&](std::size_t first, std::size_t) {
        if (first == 0) {
            d.texels.resize(w * h);
        } else {
            d.cdf.resize((h + 1) + h * (w + 1));
        }
    });
    std::vector<double> rowWeight(h);
    std::vector<glm::dvec3> rowIntegral(h);
    // Each row: its texels encoded, its cdf over columns of luminance × sin θ (decoded values, so
    // that what is sampled is what is seen), normalised; its weight and solid-angle integral.
    parallelFor(h, 16, [&](std::size_t first, std::size_t last) {
        std::vector<double> prefix(w + 1);
        for (std::size_t y = first; y < last; ++y) {
            double theta0 = PI * double(y) / double(h);
            double theta1 = PI * double(y + 1) / double(h);
            double sinTheta = std::sin(0.5 * (theta0 + theta1));
            double texelSolidAngle = (2.0 * double(PI) / double(w)) * (std::cos(theta0) - std::cos(theta1));
            glm::dvec3 rowSum(0.0);
            prefix[0] = 0.0;
            for (std::size_t x = 0; x < w; ++x) {
                std::uint32_t texel = encodeRgbe(map.texels[y * w + x]);
                d.texels[y * w + x] = texel;
                glm::vec3 c = decodeRgbe(texel);
                rowSum += glm::dvec3(c);
                prefix[x + 1] = prefix[x] + double(0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z) * sinTheta;
            }
            glm::dvec3 integral = rowSum * texelSolidAngle;
            float* row = &d.cdf[(h + 1) + y * (w + 1)];
            double total = prefix[w];
            for (std::size_t x = 0; x <= w; ++x) {
                row[x] = total > 0.0 ? float(prefix[x] / total) : float(double(x) / double(w));
            }
            row[w] = 1.0f;
            rowWeight[y] = total;
            rowIntegral[y] = integral;
        }
    });
    double total = 0.0;
    for (std::size_t y = 0; y < h; ++y) {
        total += rowWeight[y];
        d.integral += rowIntegral[y];
    }
    double cdf = 0.0;
    d.cdf[0] = 0.0f;
    for (std::size_t y = 0; y < h; ++y) {
        cdf += total > 0.0 ? rowWeight[y] / total : 1.0 / double(h);
        d.cdf[y + 1] = float(cdf);
    }
    d.cdf[h] = 1.0f;
    return d;
}

glm::mat3 environmentRotation(float degrees, glm::vec3 axis) {
    return glm::mat3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(axis)));
}

}  // namespace photon
