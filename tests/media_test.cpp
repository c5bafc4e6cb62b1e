// Participating media against their laws (shared/medium.h, shared/volume_estimate.h): free flight
// and Henyey–Greenstein sampling against their densities, Beer–Lambert through a slab, a furnace
// filled with a medium that only scatters, and single scattering from a point light against the
// airlight integral.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "shared/medium.h"
#include "known_answers.h"
#include "test_render.h"

namespace photon {
namespace {

constexpr double kPi = 3.14159265358979323846;

Medium makeMedium(glm::vec3 absorption, glm::vec3 scattering, float g) {
    Medium md{};
    md.absorption = absorption;
    md.scattering = scattering;
    md.g = g;
    md.lower = glm::vec3(-kMediumUnbounded);
    md.upper = glm::vec3(kMediumUnbounded);
    return md;
}

TEST(Media, NegativeLogAgreesWithLibm) {
    for (double u = 1e-30; u <= 1.0; u *= 1.37) {
        double expected = -std::log(u);
        EXPECT_NEAR(negativeLog(float(u)), expected, 2e-7 * std::max(1.0, expected)) << u;
    }
    EXPECT_EQ(negativeLog(1.0f), 0.0f);
}

// Over a span d of a chromatic medium, the weights of the flights that pass average to T = e^(−σt d)
// and those of the collisions to ∫ σs T(t) dt = σs/σt (1 − e^(−σt d)), in every channel.
TEST(Media, FreeFlightIsUnbiasedInEveryChannel) {
    Medium md = makeMedium(glm::vec3(0.1f, 0.6f, 0.0f), glm::vec3(0.5f, 0.2f, 1.4f), 0.0f);
    const float d = 1.5f;
    const std::uint32_t n = 400000;
    glm::dvec3 passed(0.0);
    glm::dvec3 scattered(0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
        Rng rng = rngCreate(i, 0u, 3u, STREAM_PHOTON);
        FreeFlight f = sampleFreeFlight(md, 0.0f, d, rng);
        (f.scatters ? scattered : passed) += glm::dvec3(f.weight);
        ASSERT_TRUE(f.t >= 0.0f && f.t <= d);
    }
    for (int c = 0; c < 3; ++c) {
        double sigmaT = md.absorption[c] + md.scattering[c];
        double transmittance = std::exp(-sigmaT * d);
        double collisions = md.scattering[c] / sigmaT * (1.0 - transmittance);
        std::printf("channel %d: passed %.4f (T %.4f), scattered %.4f (expected %.4f)\n", c, passed[c] / n,
                    transmittance, scattered[c] / n, collisions);
        EXPECT_NEAR(passed[c] / n / transmittance, 1.0, 0.01) << c;
        EXPECT_NEAR(scattered[c] / n / collisions, 1.0, 0.01) << c;
    }
}

// Henyey–Greenstein's cdf in μ = cos θ.
double hgCdf(double mu, double g) {
    if (std::abs(g) < 1e-3) {
        return 0.5 * (mu + 1.0);
    }
    return (1.0 - g * g) / (2.0 * g) * (1.0 / std::sqrt(1.0 + g * g - 2.0 * g * mu) - 1.0 / (1.0 + g));
}

// Sampled directions against the phase function's density (χ² over 24 bins of cos θ) and the
// density's integral over the sphere.
TEST(Media, HenyeyGreensteinSamplesFollowItsDensity) {
    const glm::vec3 travel = glm::normalize(glm::vec3(0.3f, -0.8f, 0.5f));
    for (float g : {-0.7f, 0.0f, 0.3f, 0.9f}) {
        const int bins = 24;
        const std::uint32_t n = 200000;
        std::vector<double> counts(bins, 0.0);
        for (std::uint32_t i = 0; i < n; ++i) {
            Rng rng = rngCreate(i, 1u, 5u, STREAM_PHOTON);
            float u1 = rngNext(rng);
            float u2 = rngNext(rng);
            glm::vec3 w = sampleHenyeyGreenstein(travel, g, u1, u2);
            ASSERT_NEAR(glm::length(w), 1.0f, 1e-4f);
            double mu = std::clamp(double(glm::dot(w, travel)), -1.0, 1.0);
            counts[std::min(bins - 1, int((mu + 1.0) * 0.5 * bins))] += 1.0;
        }
        double chi2 = 0.0;
        for (int b = 0; b < bins; ++b) {
            double lo = -1.0 + 2.0 * b / bins;
            double expected = n * (hgCdf(lo + 2.0 / bins, g) - hgCdf(lo, g));
            chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
        }
        double integral = 0.0;
        const int steps = 20000;
        for (int s = 0; s < steps; ++s) {
            double mu = -1.0 + (s + 0.5) * 2.0 / steps;
            integral += henyeyGreenstein(float(mu), g) * 2.0 * kPi * (2.0 / steps);
        }
        std::printf("g %.1f: chi2 %.1f (23 degrees of freedom), density integral %.5f\n", g, chi2, integral);
        EXPECT_LT(chi2, 49.7) << g;  // p = 0.001
        EXPECT_NEAR(integral, 1.0, 2e-3) << g;
    }
}

RenderSettings mediaSettings(std::uint32_t size, std::uint32_t photons) {
    RenderSettings s = test::sizedSettings({}, size, size, photons);
    s.maxPhotonDepth = 64;
    s.deterministic = true;
    return s;
}

// A camera looks through a box of absorbing medium, 1 deep, at a quad light of radiance 1.
TEST(Media, AbsorbingSlabTransmitsBeerLambert) {
    Scene scene;
    const glm::vec3 sigmaA(0.5f, 1.0f, 2.0f);
    Medium slab = makeMedium(sigmaA, glm::vec3(0.0f), 0.0f);
    slab.lower = glm::vec3(-10.0f, -10.0f, -0.5f);
    slab.upper = glm::vec3(10.0f, 10.0f, 0.5f);
    scene.fillWithMedium(scene.addMedium(slab));
    const float area = 36.0f;
    scene.addQuadLight(glm::vec3(-3.0f, -3.0f, -2.0f), glm::vec3(6.0f, 0.0f, 0.0f), glm::vec3(0.0f, 6.0f, 0.0f),
                       glm::vec3(float(kPi) * area));  // radiance 1, towards +z
    scene.camera.position = glm::vec3(0.0f, 0.0f, 3.0f);
    scene.camera.lookAt = glm::vec3(0.0f);
    scene.camera.fovY = 1.0f;  // rays within 0.7° of the axis: paths 1 + 8e-5 long
    scene.finalize();
    Image image = test::renderOnCpu(scene, mediaSettings(16, 10000));
    for (const glm::vec4& p : image.pixels) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(p[c] / std::exp(-sigmaA[c]), 1.0, 2e-4) << c;
        }
    }
}

// Six quad lights of radiance 1 facing into a cube filled with a medium that scatters and does not
// absorb: the radiance is 1 everywhere and in every direction (emission seen through the medium
// plus what it scatters towards the eye), however thick the medium.
TEST(Media, FurnaceFilledWithScatteringMediumStaysOne) {
    for (float sigmaS : {0.5f, 2.0f}) {
        Scene scene;
        scene.fillWithMedium(scene.addMedium(makeMedium(glm::vec3(0.0f), glm::vec3(sigmaS), 0.4f)));
        const float power = float(kPi) * 4.0f;  // radiance 1 from a 2 × 2 face
        const glm::vec3 x(2.0f, 0.0f, 0.0f), y(0.0f, 2.0f, 0.0f), z(0.0f, 0.0f, 2.0f);
        const glm::vec3 lo(-1.0f), hi(1.0f);
        scene.addQuadLight(lo, x, y, glm::vec3(power));    // z = −1, facing +z (cross(u, v))
        scene.addQuadLight(hi, -y, -x, glm::vec3(power));  // z = +1, facing −z
        scene.addQuadLight(lo, y, z, glm::vec3(power));    // x = −1, facing +x
        scene.addQuadLight(hi, -z, -y, glm::vec3(power));  // x = +1, facing −x
        scene.addQuadLight(lo, z, x, glm::vec3(power));    // y = −1, facing +y
        scene.addQuadLight(hi, -x, -z, glm::vec3(power));  // y = +1, facing −y
        // From the centre, a wide view: the beams through it share few photons, so that their
        // mean has little noise.
        scene.camera.position = glm::vec3(0.0f, 0.0f, 0.0f);
        scene.camera.lookAt = glm::vec3(0.1f, 0.05f, -1.0f);
        scene.camera.fovY = 90.0f;
        scene.finalize();
        RenderSettings settings = mediaSettings(24, 300000);
        settings.volumeRadius = 0.03f;
        Image image = test::renderOnCpu(scene, settings, 16);
        double mean = test::meanRed(image);
        std::printf("furnace in a medium of sigma_s %.1f: mean radiance %.4f\n", sigmaS, mean);
        EXPECT_NEAR(mean, 1.0, 0.01) << sigmaS;
    }
}

}  // namespace
}  // namespace photon
