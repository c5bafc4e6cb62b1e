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
    Medium md = homogeneousMedium();
    md.absorption = absorption;
    md.scattering = scattering;
    md.g = g;
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
        FreeFlight f = sampleFreeFlight(Bindings{}, md, glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), 0.0f, d, rng);
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

// The light a homogeneous medium scatters once towards the eye along the ray o + t·dir, t ∈ (0, ∞),
// from an isotropic point light of intensity I at distance D from o, at angle γ from the ray.
// With h = D sin γ the light's distance from the ray's line and t − D cos γ = h tan ξ, the
// integral σs I ∫ p(θ) e^(−σt (t + d(t))) / d(t)² dt becomes one over ξ ∈ (γ − π/2, π/2) of a
// smooth integrand (cos θ = −sin ξ between the light's travel and the way to the eye), here by
// Simpson's rule.
double singleScattering(double sigmaS, double sigmaT, double g, double intensity, double D, double gamma) {
    double h = D * std::sin(gamma);
    auto integrand = [&](double xi) {
        double mu = -std::sin(xi);
        double phase = (1.0 - g * g) / (4.0 * kPi * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
        double c = std::cos(xi);
        return c <= 1e-12 ? 0.0 : phase * std::exp(-sigmaT * h * (std::tan(xi) + 1.0 / c));
    };
    const int n = 20000;
    double a = gamma - 0.5 * kPi;
    double step = (0.5 * kPi - a) / n;
    double sum = integrand(a) + integrand(0.5 * kPi);
    for (int i = 1; i < n; ++i) {
        sum += integrand(a + i * step) * (i % 2 == 1 ? 4.0 : 2.0);
    }
    return sigmaS * intensity * std::exp(-sigmaT * D * std::cos(gamma)) / h * sum * step / 3.0;
}

// Sun, Ramamoorthi, Narasimhan & Nayar (SIGGRAPH 2005), the airlight integral for an isotropic
// medium: L = A0 (F(A1, π/2) − F(A1, γ/2)) for a ray to infinity, A0 = σs I e^(−T cos γ) / (2π D sin γ),
// A1 = T sin γ, T = σt D, and their special function F(u, v) = ∫₀^v e^(−u tan ξ) dξ (tabulated in
// the paper; Simpson's rule here).
double airlight(double sigmaS, double sigmaT, double intensity, double D, double gamma) {
    auto F = [](double u, double v) {
        const int n = 20000;
        double step = v / n;
        auto f = [&](double xi) { return xi >= 0.5 * kPi - 1e-12 ? 0.0 : std::exp(-u * std::tan(xi)); };
        double sum = f(0.0) + f(v);
        for (int i = 1; i < n; ++i) {
            sum += f(i * step) * (i % 2 == 1 ? 4.0 : 2.0);
        }
        return sum * step / 3.0;
    };
    double T = sigmaT * D;
    double a0 = sigmaS * intensity * std::exp(-T * std::cos(gamma)) / (2.0 * kPi * D * std::sin(gamma));
    double a1 = T * std::sin(gamma);
    return a0 * (F(a1, 0.5 * kPi) - F(a1, 0.5 * gamma));
}

TEST(Media, AirlightClosedFormAgreesWithTheIntegral) {
    for (double gamma : {0.2, 0.8, 1.6, 2.5}) {
        for (double sigmaT : {0.3, 1.0, 3.0}) {
            double closed = airlight(0.7 * sigmaT, sigmaT, 2.0, 1.7, gamma);
            EXPECT_NEAR(singleScattering(0.7 * sigmaT, sigmaT, 0.0, 2.0, 1.7, gamma) / closed, 1.0, 1e-6) << gamma;
        }
    }
}

// A point light in a homogeneous medium that fills everything, photons stored at their first
// scattering only (max_photon_depth 1): what the camera sees is single scattering, which the
// airlight integral gives in closed form. The image's columns, in four bands across γ from about
// 15° to 55°, against it averaged over each pixel; isotropic, and forward-scattering by the
// integral itself.
TEST(Media, SingleScatteringMatchesTheAirlightIntegral) {
    struct Case {
        float sigmaS;
        float sigmaA;
        float g;
    };
    for (Case c : {Case{0.5f, 0.3f, 0.0f}, Case{0.6f, 0.1f, 0.5f}}) {
        Scene scene;
        Medium md = makeMedium(glm::vec3(c.sigmaA), glm::vec3(c.sigmaS), c.g);
        md.lower = glm::vec3(-14.0f);
        md.upper = glm::vec3(14.0f);
        scene.fillWithMedium(scene.addMedium(md));
        const double power = 4.0 * kPi;  // intensity 1
        scene.addPointLight(glm::vec3(0.0f), glm::vec3(float(power)));
        const float D = 2.0f;
        const float turn = 35.0f * float(kPi) / 180.0f;  // the view's axis from the light's direction
        scene.camera.position = glm::vec3(0.0f, 0.0f, D);
        scene.camera.lookAt = scene.camera.position + glm::vec3(std::sin(turn), 0.0f, -std::cos(turn));
        scene.camera.fovY = 40.0f;
        scene.finalize();
        const std::uint32_t size = 32;
        RenderSettings settings = test::sizedSettings({}, size, size, 1000000);
        settings.maxPhotonDepth = 1;
        settings.deterministic = true;
        settings.grid = GridKind::Hashed;  // photons anywhere in the medium, not clamped to a cube
        settings.volumeRadius = 0.1f;  // wide (every ray passes the light at over 0.5): 16 frames are within 1%
        Image image = test::renderOnCpu(scene, settings, 16);
        // The expected image: the integral over 4 × 4 places in each pixel.
        Camera camera = makeCamera(scene.camera, size, size);
        const glm::dvec3 light(0.0);
        const double sigmaT = c.sigmaS + c.sigmaA;
        const int bands = 4;
        std::vector<double> rendered(bands, 0.0), expected(bands, 0.0);
        for (std::uint32_t y = 0; y < size; ++y) {
            for (std::uint32_t x = 0; x < size; ++x) {
                double sum = 0.0;
                for (int s = 0; s < 16; ++s) {
                    float sx = (2.0f * (float(x) + (s % 4 + 0.5f) / 4.0f) / float(size) - 1.0f) * camera.tanHalfFovY * camera.aspect;
                    float sy = (1.0f - 2.0f * (float(y) + (s / 4 + 0.5f) / 4.0f) / float(size)) * camera.tanHalfFovY;
                    glm::dvec3 dir = glm::normalize(glm::dvec3(camera.forward + sx * camera.right + sy * camera.up));
                    glm::dvec3 toLight = light - glm::dvec3(camera.position);
                    double gamma = std::acos(glm::dot(dir, glm::normalize(toLight)));
                    sum += singleScattering(c.sigmaS, sigmaT, c.g, power / (4.0 * kPi), glm::length(toLight), gamma);
                }
                int band = int(x * bands / size);
                expected[band] += sum / 16.0;
                rendered[band] += image.pixels[y * size + x].r;
            }
        }
        for (int b = 0; b < bands; ++b) {
            std::printf("sigma_s %.1f sigma_a %.1f g %.1f, band %d: rendered %.5f, airlight %.5f (%+.2f%%)\n", c.sigmaS,
                        c.sigmaA, c.g, b, rendered[b] / (size * size / bands), expected[b] / (size * size / bands),
                        100.0 * (rendered[b] / expected[b] - 1.0));
            EXPECT_NEAR(rendered[b] / expected[b], 1.0, 0.02) << "band " << b << ", g " << c.g << ", sigma_a " << c.sigmaA;
        }
    }
}

}  // namespace
}  // namespace photon
