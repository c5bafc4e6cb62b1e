// Spectral rendering (shared/spectral.h, core/spectral/): the observer and the primaries, the
// frames' wavelengths averaging to white, the dispersion law; and renders with known answers on
// the CPU: the furnace, a non-dispersive scene as in RGB, the ball lens focusing each wavelength
// where n(λ) puts it, and a prism bending each wavelength as Snell's law does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/render/devices.h"
#include "core/loaders/scene_loader.h"
#include "core/spectral/spectrum.h"
#include "known_answers.h"
#include "test_util.h"

namespace photon {
namespace {

glm::dvec3 colourOf(const std::function<double(double)>& spectrum) {
    glm::dvec3 sum(0.0);
    const double step = 0.05;
    for (double x = kVisibleMin + 0.5 * step; x < kVisibleMax; x += step) {
        sum += rgbFromXyz(cie1931(x)) * spectrum(x);
    }
    return sum * step;
}

TEST(Spectrum, PrimariesAreReflectancesThatSumToOneAndGiveTheSrgbPrimaries) {
    const SpectralPrimaries& p = spectralPrimaries();
    for (const glm::dvec3& v : p.values) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(v[c], 0.0);
            EXPECT_LE(v[c], 1.0 + 1e-9);
        }
        EXPECT_NEAR(v.x + v.y + v.z, 1.0, 1e-9);
    }
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 colour = colourOf([&](double x) { return p.at(x)[k]; });
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(colour[c], k == c ? 1.0 : 0.0, 1e-3) << "primary " << k << " channel " << c;
        }
    }
    glm::dvec3 white = colourOf([](double) { return 1.0; });
    EXPECT_NEAR(white.x, 1.0, 1e-9);
    EXPECT_NEAR(white.y, 1.0, 1e-9);
    EXPECT_NEAR(white.z, 1.0, 1e-9);
}

TEST(Spectrum, VisibleWavelengthsInvertTheirCdfAndIntegrateToOne) {
    double integral = 0.0;
    for (double x = kVisibleMin; x < kVisibleMax; x += 0.01) {
        integral += visibleWavelengthPdf(x + 0.005) * 0.01;
    }
    EXPECT_NEAR(integral, 1.0, 1e-3);
    EXPECT_NEAR(sampleVisibleWavelength(0.0), kVisibleMin, 0.5);
    EXPECT_NEAR(sampleVisibleWavelength(1.0 - 1e-12), kVisibleMax, 0.5);
    // The cdf at the u-th sample is u.
    for (double u : {0.1, 0.37, 0.5, 0.81}) {
        double lambda = sampleVisibleWavelength(u);
        double cdf = 0.0;
        for (double x = kVisibleMin; x < lambda; x += 0.01) {
            cdf += visibleWavelengthPdf(x + 0.005) * 0.01;
        }
        EXPECT_NEAR(cdf, u, 2e-3) << u;
    }
}

// A flat spectrum seen through the frames' wavelength sets: white on average, and closer the more
// frames (the heroes step along a golden-ratio sequence).
TEST(Spectrum, FramesAverageAFlatSpectrumToWhite) {
    double previous = 1.0;
    for (std::uint32_t frames : {4u, 16u, 256u}) {
        glm::dvec3 sum(0.0);
        for (std::uint32_t f = 0; f < frames; ++f) {
            SpectralParams s = frameSpectrum(f, 1u, 0.0f);
            sum += glm::dvec3(glm::dot(glm::vec3(s.toRgb0), glm::vec3(1.0f)), glm::dot(glm::vec3(s.toRgb1), glm::vec3(1.0f)),
                              glm::dot(glm::vec3(s.toRgb2), glm::vec3(1.0f)));
        }
        glm::dvec3 mean = sum / double(frames);
        double error = glm::length(mean - glm::dvec3(1.0));
        std::printf("flat spectrum over %u frames: rgb (%.4f, %.4f, %.4f)\n", frames, mean.x, mean.y, mean.z);
        EXPECT_LT(error, previous) << frames;
        previous = error;
    }
    EXPECT_LT(previous, 0.005);
}

TEST(Spectrum, DispersionFollowsTheAbbeNumber) {
    for (double abbe : {59.0, 32.0, 9.8}) {
        double nd = 1.5;
        double d = 20.0 / abbe;
        EXPECT_NEAR(dispersedIor(nd, d, 587.56), nd, 1e-4);
        double measured = (nd - 1.0) / (dispersedIor(nd, d, 486.13) - dispersedIor(nd, d, 656.27));
        EXPECT_NEAR(measured / abbe, 1.0, 0.01) << abbe;
    }
    EXPECT_EQ(dispersedIor(1.5, 0.0, 450.0), 1.5);
    EXPECT_EQ(dispersedIor(1.01, 1e5, 830.0), 1.0);  // never below 1
}

// The frame's parameters under --spectral: the flag, the three wavelengths, and the one given.
TEST(Spectrum, FixedWavelengthFillsEverySample) {
    SpectralParams s = frameSpectrum(3u, 9u, 550.0f);
    EXPECT_EQ(s.wavelengths.x, 550.0f);
    EXPECT_EQ(s.wavelengths.z, 550.0f);
    EXPECT_NEAR(s.toRgb0.x + s.toRgb0.y + s.toRgb0.z, 1.0f, 1e-6f);
    SpectralParams a = frameSpectrum(0u, 1u, 0.0f);
    SpectralParams b = frameSpectrum(1u, 1u, 0.0f);
    EXPECT_NE(a.wavelengths.x, b.wavelengths.x);
    for (const SpectralParams& p : {a, b}) {
        for (int i = 0; i < 3; ++i) {
            EXPECT_GE(p.wavelengths[i], kVisibleMin);
            EXPECT_LE(p.wavelengths[i], kVisibleMax);
        }
    }
}

TEST(SpectralRender, FurnaceRadianceAsInRgb) {
    const float R = 2.0f;
    const float rho = 0.5f;
    const float phi = 10.0f;
    Scene scene = test::furnaceScene(rho, phi, [&](Scene& s, std::uint32_t wall) { s.addSphere(glm::vec3(0.0f), R, wall); });
    for (Estimator estimator : {Estimator::Radius, Estimator::Sppm}) {
        RenderSettings settings = test::furnaceSettings(estimator);
        settings.spectral = true;
        settings.frames = 256;  // the frames' wavelengths average to white within 0.5% (above)
        settings.photons = 20000;
        Image image = test::renderOnCpu(scene, settings, settings.frames);
        double expected = test::furnaceRadiance(R, rho, phi);
        glm::dvec3 mean(0.0);
        for (const glm::vec4& p : image.pixels) {
            mean += glm::dvec3(p);
        }
        mean /= double(image.pixels.size()) * expected;
        std::printf("spectral furnace %s: mean/expected (%.4f, %.4f, %.4f)\n", toString(estimator), mean.x, mean.y, mean.z);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(mean[c], 1.0, 0.01) << toString(estimator) << " channel " << c;
        }
    }
}

// The Cornell box has no dispersive material: spectral and RGB converge to the same image (its
// coloured walls' interreflections differ only as the products of their spectra differ from the
// products of their RGBs).
TEST(SpectralRender, NonDispersiveSceneMatchesRgb) {
    Scene scene = defaultScene();
    RenderSettings settings = test::sizedSettings(scene.render, 48, 36, 20000);
    Image rgb = test::renderOnCpu(scene, settings, 256);
    settings.spectral = true;
    Image spectral = test::renderOnCpu(scene, settings, 256);
    glm::dvec3 a(0.0), b(0.0);
    for (std::size_t i = 0; i < rgb.pixels.size(); ++i) {
        a += glm::dvec3(rgb.pixels[i]);
        b += glm::dvec3(spectral.pixels[i]);
    }
    double error = relativeRmse(spectral, rgb);
    std::printf("cornell spectral / rgb means (%.4f, %.4f, %.4f), relative RMSE %.4f\n", b.x / a.x, b.y / a.y, b.z / a.z,
                error);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(b[c] / a[c], 1.0, 0.01) << "channel " << c;
    }
    EXPECT_LT(error, 0.05);
}

// Dispersion moves light between wavelengths' directions but neither makes nor loses any: the
// caustic scene with an Abbe number of 30 has the image mean it has without one.
TEST(SpectralRender, DispersionKeepsTheEnergy) {
    Scene plain = loadSceneFile(test::scenesDir() + "/caustic.json");
    Scene dispersive = plain;
    dispersive.materials[dispersive.findMaterial("glass")].dispersion = 20.0f / 30.0f;
    RenderSettings settings = test::sizedSettings(plain.render, 64, 48, 50000);
    settings.spectral = true;
    glm::dvec3 mean[2];
    for (int d = 0; d < 2; ++d) {
        Image image = test::renderOnCpu(d ? dispersive : plain, settings, 96);
        mean[d] = glm::dvec3(0.0);
        for (const glm::vec4& p : image.pixels) {
            mean[d] += glm::dvec3(p);
        }
    }
    std::printf("caustic scene, dispersive / not: means (%.4f, %.4f, %.4f)\n", mean[1].x / mean[0].x,
                mean[1].y / mean[0].y, mean[1].z / mean[0].z);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(mean[1][c] / mean[0][c], 1.0, 0.01) << "channel " << c;
    }
}

TEST(SpectralRender, SameSeedSameImage) {
    Scene scene = loadSceneFile(test::scenesDir() + "/prism.json");
    RenderSettings settings = test::sizedSettings(scene.render, 40, 25, 20000);
    Image a = test::renderOnCpu(scene, settings, 3);
    Image b = test::renderOnCpu(scene, settings, 3);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)));
    EXPECT_TRUE(allFinite(a));
}

// The ball lens of dispersive glass (Abbe number 20) lit at one wavelength at a time focuses at
// n(λ)R / (2(n(λ) - 1)): blue nearer than red.
TEST(SpectralRender, BallLensFocusesEachWavelengthAtItsIndex) {
    const float nd = 1.5f;
    const float abbe = 20.0f;
    double previous = 0.0;
    for (float lambda : {450.0f, 550.0f, 650.0f}) {
        double n = dispersedIor(nd, 20.0 / abbe, lambda);
        double focus = test::paraxialFocus(float(n));
        Scene lens = test::ballLensScene(nd, [&](Scene& s, std::uint32_t glass) {
            s.materials[glass].dispersion = 20.0f / abbe;
            s.addSphere(glm::vec3(0.0f), 1.0f, glass);
        });
        RenderSettings settings;
        settings.wavelength = lambda;
        test::CausticPeak peak = test::findCausticPeak(lens, 0.001f, settings, 1.36f);
        std::printf("ball lens at %.0f nm (n = %.4f): peak at z = %.3f, paraxial focus %.3f\n", lambda, n, peak.z, focus);
        test::expectPeakAtFocus(peak, focus);
        EXPECT_GT(peak.z, previous) << lambda << " nm focuses no farther than a shorter wavelength";
        previous = peak.z;
    }
}

// A 60° prism of dispersive glass (n_d 1.6, Abbe number 12) in a narrow beam at 50° incidence: the
// caustic photons on a screen behind it lie where Snell's law at both faces sends each wavelength.
struct Prism {
    glm::dvec3 entry{-0.2, 0.3, -0.11547};   // the middle of the face the beam enters
    glm::dvec3 beam{std::cos(-20.0 * test::kPi / 180.0), 0.0, std::sin(-20.0 * test::kPi / 180.0)};
    glm::dvec3 entryNormal{-std::sqrt(3.0) / 2.0, 0.0, -0.5};  // outward
    glm::dvec3 exitPoint{0.4, 0.0, 0.2309401};                   // a point of the exit face
    glm::dvec3 exitNormal{std::sqrt(3.0) / 2.0, 0.0, -0.5};      // outward
    double screenX = 2.5;
};

glm::dvec3 refracted(const glm::dvec3& d, const glm::dvec3& outward, double eta) {  // eta = n_from / n_to
    glm::dvec3 n = glm::dot(d, outward) < 0.0 ? outward : -outward;  // facing the incoming ray
    double cosI = -glm::dot(d, n);
    double k = 1.0 - eta * eta * (1.0 - cosI * cosI);
    return eta * d + (eta * cosI - std::sqrt(k)) * n;
}

// Where the beam's central ray leaves the prism, and its direction, for index n.
std::pair<glm::dvec3, glm::dvec3> exitRay(const Prism& p, double n) {
    glm::dvec3 inside = refracted(p.beam, p.entryNormal, 1.0 / n);
    double t = glm::dot(p.exitPoint - p.entry, p.exitNormal) / glm::dot(inside, p.exitNormal);
    glm::dvec3 x = p.entry + inside * t;
    return {x, refracted(inside, p.exitNormal, n)};
}

TEST(SpectralRender, PrismBendsEachWavelengthAsSnellsLaw) {
    Scene base = loadSceneFile(test::scenesDir() + "/prism.json");
    Prism prism;
    for (float lambda : {450.0f, 550.0f, 650.0f}) {
        Scene scene = base;
        RenderSettings settings = test::sizedSettings(scene.render, 4, 4, 200000);
        settings.wavelength = lambda;
        settings.causticFraction = 0.99f;
        auto backend = createRenderer("cpu");
        backend->setScene(std::move(scene));
        backend->setSettings(settings);
        backend->renderFrame();
        PhotonMaps maps = backend->readPhotonMaps();
        double n = dispersedIor(1.6, 20.0 / 12.0, lambda);
        auto [exit, direction] = exitRay(prism, n);
        double predicted = std::atan2(direction.z, direction.x);
        // The photons on the screen near the beam (the prism's faces also reflect a little
        // elsewhere): their mean direction from the exit point.
        double sumZ = 0.0, weight = 0.0;
        for (const Photon& ph : maps.photons[MAP_CAUSTIC]) {
            double z = exit.z + direction.z / direction.x * (prism.screenX - exit.x);
            if (std::abs(ph.position.x - prism.screenX) < 1e-3 && std::abs(ph.position.z - z) < 0.3 &&
                std::abs(ph.position.y - 0.3) < 0.3) {
                double w = ph.power.x + ph.power.y + ph.power.z;
                sumZ += ph.position.z * w;
                weight += w;
            }
        }
        ASSERT_GT(weight, 0.0) << lambda;
        double measured = std::atan2(sumZ / weight - exit.z, prism.screenX - exit.x);
        double degrees = (measured - predicted) * 180.0 / test::kPi;
        std::printf("prism at %.0f nm (n = %.4f): exit angle %.3f deg, Snell %.3f deg\n", lambda, n,
                    measured * 180.0 / test::kPi, predicted * 180.0 / test::kPi);
        EXPECT_NEAR(degrees, 0.0, 0.5) << lambda << " nm";
    }
}

}  // namespace
}  // namespace photon
