#include "core/spectral/spectrum.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace photon {
namespace {

// exp(-(x - μ)² / 2σ²) with σ1 below μ and σ2 above (Wyman et al. 2013, eq. 1).
double lobe(double x, double mu, double sigmaBelow, double sigmaAbove) {
    double t = (x - mu) / (x < mu ? sigmaBelow : sigmaAbove);
    return std::exp(-0.5 * t * t);
}

// ∫ f(λ) dλ over the visible range, by the midpoint rule at 0.05 nm (the observer's narrowest
// lobe has σ = 11.8 nm).
template <typename F>
glm::dvec3 integrateVisible(F f) {
    constexpr double kStep = 0.05;
    glm::dvec3 sum(0.0);
    for (double x = kVisibleMin + 0.5 * kStep; x < kVisibleMax; x += kStep) {
        sum += f(x);
    }
    return sum * kStep;
}

glm::dvec3 linearSrgbFromXyz(const glm::dvec3& xyz) {
    // IEC 61966-2-1 (sRGB), XYZ to linear RGB; glm is column-major.
    const glm::dmat3 m(3.2404542, -0.9692660, 0.0556434, -1.5371385, 1.8760108, -0.2040259, -0.4985314, 0.0415560,
                       1.0572252);
    return m * xyz;
}

// The flat spectrum's linear sRGB, for the white balance.
const glm::dvec3& flatWhite() {
    static const glm::dvec3 white = integrateVisible([](double x) { return linearSrgbFromXyz(cie1931(x)); });
    return white;
}

// Solves a x = b by Gaussian elimination with partial pivoting (a is n × n, row-major).
std::vector<double> solveDense(std::vector<double> a, std::vector<double> b) {
    std::size_t n = b.size();
    for (std::size_t col = 0; col < n; ++col) {
        std::size_t pivot = col;
        for (std::size_t r = col + 1; r < n; ++r) {
            if (std::abs(a[r * n + col]) > std::abs(a[pivot * n + col])) {
                pivot = r;
            }
        }
        if (pivot != col) {
            for (std::size_t c = 0; c < n; ++c) {
                std::swap(a[col * n + c], a[pivot * n + c]);
            }
            std::swap(b[col], b[pivot]);
        }
        for (std::size_t r = col + 1; r < n; ++r) {
            double f = a[r * n + col] / a[col * n + col];
            if (f == 0.0) {
                continue;
            }
            for (std::size_t c = col; c < n; ++c) {
                a[r * n + c] -= f * a[col * n + c];
            }
            b[r] -= f * b[col];
        }
    }
    std::vector<double> x(n);
    for (std::size_t i = n; i-- > 0;) {
        double s = b[i];
        for (std::size_t c = i + 1; c < n; ++c) {
            s -= a[i * n + c] * x[c];
        }
        x[i] = s / a[i * n + i];
    }
    return x;
}

// The primaries: minimise Σ (first differences)² (+ a tiny ridge) subject to the three summing to
// 1 at every grid wavelength and R's and G's colours being (1, 0, 0) and (0, 1, 0) (B's follows),
// by the KKT system of that quadratic programme; values that come out negative are fixed at 0
// and the system solved again (an active set that only grows), until none is.
SpectralPrimaries solvePrimaries() {
    constexpr int n = SpectralPrimaries::kCount;
    constexpr double h = SpectralPrimaries::kStep;
    // colour[c][j]: channel c of the colour of the grid's j-th hat function (the spectrum linear
    // between the grid points, 1 at point j).
    std::vector<glm::dvec3> colour(n);
    for (int j = 0; j < n; ++j) {
        double centre = kVisibleMin + j * h;
        colour[j] = integrateVisible([&](double x) {
                        double hat = std::max(0.0, 1.0 - std::abs(x - centre) / h);
                        return hat == 0.0 ? glm::dvec3(0.0) : rgbFromXyz(cie1931(x)) * hat;
                    });
    }
    std::vector<bool> fixed(3 * n, false);
    std::vector<double> values(3 * n, 0.0);
    for (int round = 0; round < 3 * n; ++round) {
        std::vector<int> index(3 * n, -1);  // unknown of each value, -1 if fixed at 0
        int unknowns = 0;
        for (int v = 0; v < 3 * n; ++v) {
            if (!fixed[v]) {
                index[v] = unknowns++;
            }
        }
        int constraints = n + 6;
        int size = unknowns + constraints;
        std::vector<double> a(std::size_t(size) * size, 0.0);
        std::vector<double> b(size, 0.0);
        auto at = [&](int r, int c) -> double& { return a[std::size_t(r) * size + c]; };
        for (int k = 0; k < 3; ++k) {
            for (int j = 0; j < n; ++j) {
                int v = index[k * n + j];
                if (v < 0) {
                    continue;
                }
                at(v, v) += 2e-6;
                for (int step : {-1, 1}) {
                    int nb = j + step;
                    if (nb < 0 || nb >= n) {
                        continue;
                    }
                    at(v, v) += 2.0;
                    int w = index[k * n + nb];
                    if (w >= 0) {
                        at(v, w) -= 2.0;
                    }
                }
            }
        }
        auto constrain = [&](int row, int v, double coefficient) {
            int u = index[v];
            if (u >= 0) {
                at(unknowns + row, u) = coefficient;
                at(u, unknowns + row) = coefficient;
            }
        };
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < 3; ++k) {
                constrain(j, k * n + j, 1.0);
            }
            b[unknowns + j] = 1.0;
        }
        for (int k = 0; k < 2; ++k) {
            for (int c = 0; c < 3; ++c) {
                int row = n + 3 * k + c;
                for (int j = 0; j < n; ++j) {
                    constrain(row, k * n + j, colour[j][c]);
                }
                b[unknowns + row] = k == c ? 1.0 : 0.0;
            }
        }
        std::vector<double> x = solveDense(std::move(a), std::move(b));
        bool negative = false;
        for (int v = 0; v < 3 * n; ++v) {
            values[v] = index[v] < 0 ? 0.0 : x[index[v]];
            if (values[v] < -1e-12) {
                fixed[v] = true;
                negative = true;
            }
        }
        if (!negative) {
            break;
        }
    }
    SpectralPrimaries p;
    for (int j = 0; j < n; ++j) {
        p.values[j] = glm::max(glm::dvec3(values[j], values[n + j], values[2 * n + j]), glm::dvec3(0.0));
    }
    return p;
}

// The cdf of |r̄| + |ḡ| + |b̄| over 1 nm bins: cdf[j] is the mass below 360 + j nm.
struct WavelengthTable {
    static constexpr double kStep = 1.0;
    std::vector<double> cdf;
};

const WavelengthTable& wavelengthTable() {
    static const WavelengthTable table = [] {
        WavelengthTable t;
        auto bins = std::size_t((kVisibleMax - kVisibleMin) / WavelengthTable::kStep);
        t.cdf.assign(bins + 1, 0.0);
        for (std::size_t j = 0; j < bins; ++j) {
            double mass = 0.0;
            for (int k = 0; k < 20; ++k) {
                double x = kVisibleMin + (double(j) + (k + 0.5) / 20.0) * WavelengthTable::kStep;
                glm::dvec3 rgb = linearSrgbFromXyz(cie1931(x)) / flatWhite();
                mass += std::abs(rgb.r) + std::abs(rgb.g) + std::abs(rgb.b);
            }
            t.cdf[j + 1] = t.cdf[j] + mass / 20.0 * WavelengthTable::kStep;
        }
        return t;
    }();
    return table;
}

double unitFromSeed(std::uint32_t seed) {
    std::uint64_t z = std::uint64_t(seed) + 0x9e3779b97f4a7c15ull;  // splitmix64's finaliser
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return double(z >> 11) * 0x1.0p-53;
}

glm::vec4 row(const glm::dvec3& v) { return glm::vec4(glm::vec3(v), 0.0f); }

}  // namespace

glm::dvec3 cie1931(double lambda) {
    double x = 1.056 * lobe(lambda, 599.8, 37.9, 31.0) + 0.362 * lobe(lambda, 442.0, 16.0, 26.7) -
               0.065 * lobe(lambda, 501.1, 20.4, 26.2);
    double y = 0.821 * lobe(lambda, 568.8, 46.9, 40.5) + 0.286 * lobe(lambda, 530.9, 16.3, 31.1);
    double z = 1.217 * lobe(lambda, 437.0, 11.8, 36.0) + 0.681 * lobe(lambda, 459.0, 26.0, 13.8);
    return {x, y, z};
}

double sampleVisibleWavelength(double u) {
    const WavelengthTable& t = wavelengthTable();
    double target = std::clamp(u, 0.0, 1.0) * t.cdf.back();
    auto bin = std::size_t(std::upper_bound(t.cdf.begin(), t.cdf.end(), target) - t.cdf.begin());
    bin = std::min(std::max(bin, std::size_t(1)), t.cdf.size() - 1);
    double below = t.cdf[bin - 1];
    double width = t.cdf[bin] - below;
    double f = width > 0.0 ? (target - below) / width : 0.5;
    return kVisibleMin + (double(bin - 1) + std::clamp(f, 0.0, 1.0)) * WavelengthTable::kStep;
}

double visibleWavelengthPdf(double lambda) {
    if (!(lambda >= kVisibleMin && lambda <= kVisibleMax)) {
        return 0.0;
    }
    const WavelengthTable& t = wavelengthTable();
    auto bin = std::min(std::size_t((lambda - kVisibleMin) / WavelengthTable::kStep), t.cdf.size() - 2);
    return (t.cdf[bin + 1] - t.cdf[bin]) / (t.cdf.back() * WavelengthTable::kStep);
}

glm::dvec3 rgbFromXyz(const glm::dvec3& xyz) { return linearSrgbFromXyz(xyz) / flatWhite(); }

glm::dvec3 SpectralPrimaries::at(double lambda) const {
    double t = (std::clamp(lambda, kVisibleMin, kVisibleMax) - kVisibleMin) / kStep;
    int j = std::min(int(t), kCount - 2);
    double f = t - j;
    return values[j] * (1.0 - f) + values[j + 1] * f;
}

const SpectralPrimaries& spectralPrimaries() {
    static const SpectralPrimaries primaries = solvePrimaries();
    return primaries;
}

double dispersedIor(double ior, double dispersion, double lambda) {
    return std::max(ior + (ior - 1.0) * dispersion * (523655.0 / (lambda * lambda) - 1.5168) / 20.0, 1.0);
}

SpectralParams frameSpectrum(std::uint32_t frameIndex, std::uint32_t seed, float fixedWavelength) {
    // The three lie a third of the cdf apart, and the hero steps by a third of the golden ratio:
    // where they fall within their thirds then follows the golden-ratio sequence, so that the
    // frames' wavelengths fill the spectrum evenly (a frame's three alone give a coloured cast;
    // sixteen frames' 48, little).
    double hero = std::fmod(unitFromSeed(seed) + double(frameIndex) * (0.6180339887498949 / 3.0), 1.0);
    glm::dvec3 lambda, toRgb[3];
    for (int i = 0; i < 3; ++i) {
        if (fixedWavelength > 0.0f) {
            lambda[i] = fixedWavelength;
            toRgb[i] = glm::dvec3(1.0 / 3.0);
        } else {
            lambda[i] = sampleVisibleWavelength(std::fmod(hero + i / 3.0, 1.0));
            toRgb[i] = rgbFromXyz(cie1931(lambda[i])) / (3.0 * visibleWavelengthPdf(lambda[i]));
        }
    }
    SpectralParams s{};
    s.wavelengths = glm::vec4(glm::vec3(lambda), 0.0f);
    for (int i = 0; i < 3; ++i) {
        s.cauchy[i] = float((523655.0 / (lambda[i] * lambda[i]) - 1.5168) / 20.0);
    }
    const SpectralPrimaries& primaries = spectralPrimaries();
    s.fromRgb0 = row(primaries.at(lambda[0]));
    s.fromRgb1 = row(primaries.at(lambda[1]));
    s.fromRgb2 = row(primaries.at(lambda[2]));
    s.toRgb0 = row({toRgb[0].r, toRgb[1].r, toRgb[2].r});
    s.toRgb1 = row({toRgb[0].g, toRgb[1].g, toRgb[2].g});
    s.toRgb2 = row({toRgb[0].b, toRgb[1].b, toRgb[2].b});
    return s;
}

}  // namespace photon
