#include "core/image/display_bytes.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "shared/tonemap.h"

namespace photon {
namespace {

std::uint32_t bitsOf(float x) {
    std::uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return bits;
}

float floatOf(std::uint32_t bits) {
    float x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

int exactCode(float x) { return int(std::lround(srgbEncode(x) * 255.0f)); }

// The codes as thresholds: code(x) = the number of v in 1..255 with threshold[v] <= x, where
// threshold[v] is the smallest float in [0, 1] whose exact code is v or more (found by bisection
// over the floats' bits, which order positive floats as their values). Looking x up among 255
// thresholds would take 8 dependent steps, so a table indexed by x's exponent and the top 7 bits
// of its mantissa holds the code at the bucket's first float: a bucket is at most 1/128 of its
// value wide, less than a code step of the sRGB curve anywhere in [0, 1] (0.44 steps just below 1,
// fewer further down), so at most one threshold falls inside it and one comparison finishes.
struct SrgbTable {
    static constexpr std::uint32_t kOne = 0x3F800000u;  // the bits of 1.0f
    static constexpr int kShift = 16;                   // 8 exponent bits, 7 mantissa bits
    float threshold[257];                               // [0] and [256] are sentinels
    unsigned char bucket[(kOne >> kShift) + 1];

    SrgbTable() {
        threshold[0] = -INFINITY;
        threshold[256] = INFINITY;
        for (int v = 1; v <= 255; ++v) {
            std::uint32_t lo = 0;
            std::uint32_t hi = kOne;  // exactCode(1) = 255 >= v
            while (lo < hi) {
                std::uint32_t mid = lo + (hi - lo) / 2;
                if (exactCode(floatOf(mid)) >= v) {
                    hi = mid;
                } else {
                    lo = mid + 1;
                }
            }
            threshold[v] = floatOf(lo);
        }
        int code = 0;
        for (std::uint32_t i = 0; i <= (kOne >> kShift); ++i) {
            float first = floatOf(i << kShift);
            while (code < 255 && threshold[code + 1] <= first) {
                ++code;
            }
            bucket[i] = static_cast<unsigned char>(code);
        }
    }

    unsigned char operator()(float x) const {
        if (!(x > 0.0f)) {
            return 0;
        }
        if (x >= 1.0f) {
            return 255;
        }
        unsigned code = bucket[bitsOf(x) >> kShift];
        return static_cast<unsigned char>(code + (x >= threshold[code + 1] ? 1u : 0u));
    }
};

const SrgbTable& srgbTable() {
    static const SrgbTable table;
    return table;
}

}  // namespace

unsigned char srgb8(float x) { return srgbTable()(x); }

void displayBytes(const glm::vec4* pixels, std::size_t count, float scale, Tonemap curve, unsigned char* rgb) {
    const SrgbTable& table = srgbTable();
    auto c = static_cast<std::uint32_t>(curve);
    // Reading the pixels from memory is most of the time left (16 bytes of RGBA each).
    for (std::size_t i = 0; i < count; ++i) {
        rgb[3 * i] = table(toneCurve(pixels[i].x, scale, c));
        rgb[3 * i + 1] = table(toneCurve(pixels[i].y, scale, c));
        rgb[3 * i + 2] = table(toneCurve(pixels[i].z, scale, c));
    }
}

}  // namespace photon
