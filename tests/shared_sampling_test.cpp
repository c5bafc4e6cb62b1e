// χ² tests of the shared samplers and the RNG, and accuracy of the polynomial trigonometry.
#include <gtest/gtest.h>

#include <cmath>

#include "shared/bsdf.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "test_util.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Rng, UniformAcrossBins) {
    constexpr int kBins = 256;
    constexpr int kDraws = 1 << 20;
    std::vector<double> observed(kBins, 0.0);
    Rng rng = rngCreate(7u, 3u, 11u, STREAM_PHOTON);
    for (int i = 0; i < kDraws; ++i) {
        float u = rngNext(rng);
        ASSERT_GE(u, 0.0f);
        ASSERT_LT(u, 1.0f);
        observed[std::min(kBins - 1, int(u * kBins))] += 1.0;
    }
    std::vector<double> expected(kBins, double(kDraws) / kBins);
    int dof = 0;
    double chi2 = test::chiSquare(observed, expected, dof);
    EXPECT_LT(chi2, test::chiSquareThreshold(dof));
}

TEST(Rng, NeighbouringStreamsAreUncorrelated) {
    // First draws of consecutive indices (photons, pixels) must not be correlated.
    constexpr int kN = 1 << 16;
    double sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
    for (int i = 0; i < kN; ++i) {
        Rng a = rngCreate(std::uint32_t(i), 0u, 1u, STREAM_CAMERA);
        Rng b = rngCreate(std::uint32_t(i + 1), 0u, 1u, STREAM_CAMERA);
        double x = rngNext(a);
        double y = rngNext(b);
        sx += x;
        sy += y;
        sxy += x * y;
        sxx += x * x;
        syy += y * y;
    }
    double cov = sxy / kN - (sx / kN) * (sy / kN);
    double corr = cov / std::sqrt((sxx / kN - sx * sx / kN / kN) * (syy / kN - sy * sy / kN / kN));
    EXPECT_LT(std::abs(corr), 0.02);
}

TEST(Rng, SameInputsSameNumbers) {
    Rng a = rngCreate(5u, 9u, 2u, STREAM_GATHER);
    Rng b = rngCreate(5u, 9u, 2u, STREAM_GATHER);
    for (int i = 0; i < 100; ++i) {
        EXPECT_EQ(rngNextUint(a), rngNextUint(b));
    }
    Rng c = rngCreate(5u, 10u, 2u, STREAM_GATHER);
    EXPECT_NE(rngNextUint(c), rngNextUint(b));
}

TEST(SinCos2Pi, MatchesLibmWithin4e7) {
    for (int i = 0; i <= 100000; ++i) {
        float u = float(i) / 100000.0f;
        float s;
        float c;
        sinCos2Pi(u, s, c);
        EXPECT_NEAR(s, std::sin(2.0 * kPi * u), 4e-7) << u;
        EXPECT_NEAR(c, std::cos(2.0 * kPi * u), 4e-7) << u;
    }
}

// Bins directions by (cosθ about +z, φ) and compares with the integral of the density.
template <typename Sampler, typename Cdf>
void expectDirectionsFollow(Sampler sample, Cdf cdfCos, int draws = 400000) {
    constexpr int kTheta = 20;
    constexpr int kPhi = 20;
    std::vector<double> observed(kTheta * kPhi, 0.0);
    Rng rng = rngCreate(1u, 2u, 3u, 4u);
    for (int i = 0; i < draws; ++i) {
        float u1 = rngNext(rng);
        float u2 = rngNext(rng);
        vec3 d = sample(u1, u2);
        ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
        double phi = std::atan2(double(d.y), double(d.x));
        phi = phi < 0 ? phi + 2 * kPi : phi;
        int ti = std::min(kTheta - 1, int((1.0 - double(d.z)) / 2.0 * kTheta));
        int pi = std::min(kPhi - 1, int(phi / (2 * kPi) * kPhi));
        observed[ti * kPhi + pi] += 1.0;
    }
    // Bin ti covers cosθ ∈ [1 - 2(ti+1)/kTheta, 1 - 2ti/kTheta]; densities here are isotropic in φ.
    std::vector<double> expected(kTheta * kPhi, 0.0);
    for (int ti = 0; ti < kTheta; ++ti) {
        double hi = 1.0 - 2.0 * ti / kTheta;
        double lo = 1.0 - 2.0 * (ti + 1) / kTheta;
        double p = cdfCos(hi) - cdfCos(lo);
        for (int pi = 0; pi < kPhi; ++pi) {
            expected[ti * kPhi + pi] = p / kPhi * draws;
        }
    }
    int dof = 0;
    double chi2 = test::chiSquare(observed, expected, dof);
    EXPECT_LT(chi2, test::chiSquareThreshold(dof)) << "dof " << dof;
}

TEST(Sampling, CosineHemisphere) {
    // P(cosθ ≤ c) = c² over the upper hemisphere.
    expectDirectionsFollow([](float u1, float u2) { return sampleCosineHemisphere(u1, u2); },
                           [](double c) { return c > 0 ? c * c : 0.0; });
}

TEST(Sampling, UniformSphere) {
    expectDirectionsFollow([](float u1, float u2) { return sampleUniformSphere(u1, u2); },
                           [](double c) { return (c + 1.0) / 2.0; });
}

TEST(Sampling, UniformCone) {
    float coneX = 0.3f;  // cosθmax = 0.7
    expectDirectionsFollow([&](float u1, float u2) { return sampleUniformCone(vec3(0, 0, 1), coneX, u1, u2); },
                           [&](double c) { return std::clamp((c - 0.7) / 0.3, 0.0, 1.0); });
}

TEST(Sampling, NarrowConeStaysInsideAndIsUniformInSolidAngle) {
    // A cone of half-angle 1e-4 rad: 1 - cos rounds to 0 in float, 1 - cos as x does not.
    float x = 5.0e-9f;
    vec3 axis = glm::normalize(vec3(0.3f, -0.5f, 0.8f));
    Rng rng = rngCreate(9u, 0u, 0u, 0u);
    double meanX = 0;
    for (int i = 0; i < 100000; ++i) {
        float u1 = rngNext(rng);
        float u2 = rngNext(rng);
        vec3 d = sampleUniformCone(axis, x, u1, u2);
        float dx = oneMinusCos(d, axis);
        EXPECT_LE(dx, x * 1.01f);
        meanX += dx;
    }
    EXPECT_NEAR(meanX / 100000 / x, 0.5, 0.01);
}

TEST(Sampling, SphereConeX) {
    // Sphere of radius 1 at distance 2: half-angle 30°, 1 - cos = 1 - √3/2.
    EXPECT_NEAR(sphereConeX(vec3(0), vec3(2, 0, 0), 1.0f), 1.0 - std::sqrt(3.0) / 2.0, 1e-7);
    EXPECT_EQ(sphereConeX(vec3(0), vec3(0.5f, 0, 0), 1.0f), 2.0f);  // inside
    // Far away: sin²/(1 + cos) keeps precision where 1 - cos would be 0.
    EXPECT_NEAR(sphereConeX(vec3(0), vec3(1000, 0, 0), 0.1f) / 5e-9, 1.0, 1e-4);
}

TEST(Sampling, GgxNormalsFollowDcos) {
    float alpha = 0.35f;
    // CDF of cosθh for density D(h)cosθh: P(cosθh ≥ c) = ... integrate numerically.
    auto density = [&](double c) { return double(ggxD(float(c), alpha)) * c * 2.0 * kPi; };
    auto cdf = [&](double c) {
        // ∫_c^1 density(c') dc', Simpson with many steps.
        if (c >= 1.0) {
            return 0.0;
        }
        double lo = std::max(c, 0.0);
        int n = 2000;
        double h = (1.0 - lo) / n;
        double s = density(lo) + density(1.0);
        for (int i = 1; i < n; ++i) {
            s += density(lo + i * h) * (i % 2 ? 4 : 2);
        }
        return s * h / 3.0;
    };
    expectDirectionsFollow([&](float u1, float u2) { return sampleGgxNormal(u1, u2, alpha); },
                           [&](double c) { return 1.0 - cdf(c); });
}

TEST(Bsdf, GlossyConservesEnergyAndSamplingMatchesEval) {
    // For each ωo: E[weight] = ∫ f cos dωi ≤ 1, and equals a brute-force integral of evalBsdf.
    Material m{};
    m.type = MATERIAL_GLOSSY;
    m.albedo = vec3(0.3f);
    m.specular = vec3(0.6f);
    m.roughness = 0.3f;
    vec3 n(0, 0, 1);
    for (float cosO : {0.9f, 0.5f, 0.2f}) {
        vec3 wo(std::sqrt(1 - cosO * cosO), 0.0f, cosO);
        Rng rng = rngCreate(3u, 0u, 0u, 0u);
        double sampled = 0.0;
        double uniform = 0.0;
        constexpr int kN = 400000;
        for (int i = 0; i < kN; ++i) {
            BsdfSample bs = sampleBsdf(m, wo, n, n, rng);
            sampled += bs.weight.x;
            float u1 = rngNext(rng);
            float u2 = rngNext(rng);
            vec3 wi = sampleUniformSphere(u1, u2);
            uniform += double(evalBsdf(m, wo, wi, n).x) * std::max(0.0f, wi.z) * 4.0 * kPi;
        }
        sampled /= kN;
        uniform /= kN;
        EXPECT_LE(sampled, 1.0);
        EXPECT_NEAR(sampled, uniform, 0.02 * uniform) << "cosθo " << cosO;
    }
}

}  // namespace
}  // namespace photon
