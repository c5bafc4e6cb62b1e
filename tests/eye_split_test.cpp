// Eye paths that split at glass and mirror coats (shared/eye_trace.h, shared/specular_split.h), on
// the CPU backend: the split keeps energy (a glass ball about the furnace's light), the Fresnel
// shares add up to a glass slab's closed-form reflectance and transmittance, and the glass
// region's error against the stored converged Cornell box falls. (Vulkan against the CPU, bit for
// bit, with the split on by default: tests/vulkan_backend_test.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/frame/glass_pixels.h"
#include "core/image/image_error.h"
#include "core/loaders/scene_loader.h"
#include "known_answers.h"
#include "test_render.h"
#include "test_util.h"

namespace photon {
namespace {

// The furnace (known_answers.h) with a glass ball centred on its point light: every photon leaves
// the ball along a radius, so the walls are lit evenly as without it, and glass loses no light, so
// every pixel, the ball's included, sees the furnace's radiance. Seen from outside the ball.
TEST(EyeSplit, GlassBallInTheFurnaceKeepsItsRadiance) {
    const float R = 2.0f;
    const float rho = 0.5f;
    const float phi = 10.0f;
    double expected = test::furnaceRadiance(R, rho, phi);
    Scene scene = test::furnaceScene(rho, phi, [&](Scene& s, std::uint32_t wall) {
        s.addSphere(glm::vec3(0.0f), R, wall);
        s.addSphere(glm::vec3(0.0f), 0.6f, s.addMaterial("glass", makeGlass(1.5f, glm::vec3(1.0f))));
    });
    scene.camera.position = glm::vec3(0.2f, 0.3f, 1.5f);
    scene.camera.lookAt = glm::vec3(0.0f);
    scene.camera.fovY = 60.0f;
    scene.finalize();
    double rmsBySplits[3] = {0.0, 0.0, 0.0};
    for (std::uint32_t splits : {0u, 2u}) {
        RenderSettings settings = test::furnaceSettings(Estimator::Radius);
        settings.causticRadius = settings.radius;
        // Every photon path: the caustic pass cannot aim from a light inside its target (the
        // walls came out 0.8% dark with half the paths aimed at the ball).
        settings.causticFraction = 0.0f;
        settings.eyeSplits = splits;
        Image image = test::renderOnCpu(scene, settings, settings.frames);
        std::vector<bool> glass = glassPixels(scene, scene.camera, settings);
        double sum = 0.0, squares = 0.0;
        std::size_t count = 0;
        for (std::size_t i = 0; i < glass.size(); ++i) {
            if (glass[i]) {
                double d = image.pixels[i].x - expected;
                sum += image.pixels[i].x;
                squares += d * d;
                ++count;
            }
        }
        ASSERT_GT(count, glass.size() / 8);
        double mean = test::meanRed(image) / expected;
        double ball = sum / double(count) / expected;
        double rms = std::sqrt(squares / double(count)) / expected;
        std::printf("glass furnace, %u splits: mean/expected %.4f, through the ball %.4f, its pixel rms %.4f\n", splits,
                    mean, ball, rms);
        EXPECT_NEAR(mean, 1.0, 0.01) << splits << " splits";
        EXPECT_NEAR(ball, 1.0, 0.01) << splits << " splits";
        rmsBySplits[splits] = rms;
    }
    EXPECT_LT(rmsBySplits[2], 0.85 * rmsBySplits[0]) << "the split leaves the ball's pixels as noisy";
}

// A glass slab (index 1.5, between z = -0.5 and 0) seen head on, with an emitter of radiance Le
// behind it or behind the camera, nothing else: the pixels show Le times the slab's
// transmittance (1 - F) / (1 + F) or reflectance 2F / (1 + F), its surfaces' reflections summed
// (F = 0.04 at normal incidence).
double slabPixels(bool emitterBehindSlab, std::uint32_t splits, double& expected) {
    Scene s;
    s.name = "slab";
    std::uint32_t glass = s.addMaterial("glass", makeGlass(1.5f, glm::vec3(1.0f)));
    s.addPlane(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), glass);
    s.addPlane(glm::vec3(0.0f, 0.0f, -0.5f), glm::vec3(0.0f, 0.0f, -1.0f), glass);
    const float power = 100.0f;
    if (emitterBehindSlab) {
        s.addQuadLight(glm::vec3(-5.0f, -5.0f, -3.0f), glm::vec3(10.0f, 0.0f, 0.0f), glm::vec3(0.0f, 10.0f, 0.0f),
                       glm::vec3(power));
    } else {
        s.addQuadLight(glm::vec3(-5.0f, -5.0f, 6.0f), glm::vec3(0.0f, 10.0f, 0.0f), glm::vec3(10.0f, 0.0f, 0.0f),
                       glm::vec3(power));
    }
    s.camera.position = glm::vec3(0.0f, 0.0f, 5.0f);
    s.camera.lookAt = glm::vec3(0.0f);
    s.camera.fovY = 4.0f;
    s.finalize();
    RenderSettings settings = test::sizedSettings({}, 24, 24, 2000);
    settings.eyeSplits = splits;
    settings.radius = 0.1f;
    settings.causticRadius = 0.1f;
    settings.frames = 16;
    Image image = test::renderOnCpu(s, settings, settings.frames);
    double le = power / (test::kPi * 100.0);
    double f = 0.04;
    expected = le * (emitterBehindSlab ? (1.0 - f) / (1.0 + f) : 2.0 * f / (1.0 + f));
    return test::meanRed(image);
}

// Two splits follow both branches at both faces: what is left to chance (a third reflection inside,
// F² of the light) moves the mean by less than 0.5%. Without splits each pixel reflects or not at
// random, and 24 × 24 × 16 paths hold the mean of the reflection (p = 0.077) to within 3.6% (one σ).
TEST(EyeSplit, FresnelSharesAddUpToTheSlabsClosedForm) {
    for (bool behind : {true, false}) {
        for (std::uint32_t splits : {0u, 2u, 4u}) {
            double expected = 0.0;
            double mean = slabPixels(behind, splits, expected);
            std::printf("slab %s, %u splits: %.5f, closed form %.5f\n", behind ? "transmits" : "reflects", splits, mean,
                        expected);
            EXPECT_NEAR(mean / expected, 1.0, splits == 0u ? 0.12 : 0.005) << (behind ? "transmitted" : "reflected")
                                                                          << ", " << splits << " splits";
        }
    }
}

// The Cornell box at 320 × 240 after 8 frames against the stored converged reference: with the
// split (the default, 2) the pixels whose camera ray meets glass are no longer salt and pepper.
TEST(EyeSplit, GlassRegionErrorFallsAgainstTheReference) {
    Scene scene = loadSceneFile(test::scenesDir() + "/cornell.json");
    Image reference = readImage(test::dataPath("cornell-320x240.pfm"));
    RenderSettings s = test::sizedSettings(scene.render, 320, 240, 25000);
    s.estimator = Estimator::Sppm;
    s.seed = 3;
    QualityMasks masks(reference, glassPixels(scene, scene.camera, s));
    Quality q[2];
    for (std::uint32_t splits : {0u, 2u}) {
        s.eyeSplits = splits;
        q[splits / 2] = measureQuality(test::renderOnCpu(scene, s, 8), reference, masks);
        std::printf("cornell, %u splits: glass %.4f (off by 25%%: %.4f), rest away from the focus %.4f (%.4f)\n", splits,
                    q[splits / 2].glass, q[splits / 2].glassOff, q[splits / 2].rest, q[splits / 2].restOff);
    }
    EXPECT_LT(q[1].glass, 0.6 * q[0].glass);
    EXPECT_LT(q[1].glassOff, 0.3 * q[0].glassOff);
    EXPECT_LE(q[1].rest, q[0].rest * 1.02);
}

}  // namespace
}  // namespace photon
